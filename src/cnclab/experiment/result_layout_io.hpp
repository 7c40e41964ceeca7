#pragma once
// The two ways of walking a result's layout (result_layout.hpp): writing a
// record into an HDF5 file, and reading one back. Each layout item is one
// call on either class; the layout is written once, in result_layout.hpp.
//
// Attribute values: std::string; double; std::size_t (int64); bool (int64
// 0/1); an enum by its to_string name (read with `parse`: bool(text, E&)).
// `optional_` items may be absent from older files: the record keeps its default.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_lm_history.hpp"
#include "cnclab/io/eigen_std.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/train/summary.hpp"

namespace cnclab {

class ResultLayoutWriter {
 public:
  static constexpr bool reading = false;
  explicit ResultLayoutWriter(H5File& file) : f_(file) {}

  void group(const std::string& g) { f_.create_group(g); }
  void attr(const std::string& g, const char* name, const std::string& v) {
    f_.set_attribute(g, name, v);
  }
  void attr(const std::string& g, const char* name, double v) { f_.set_attribute(g, name, v); }
  void attr(const std::string& g, const char* name, std::size_t v) {
    f_.set_attribute(g, name, static_cast<std::int64_t>(v));
  }
  void attr(const std::string& g, const char* name, bool v) {
    f_.set_attribute(g, name, static_cast<std::int64_t>(v ? 1 : 0));
  }
  template <class T>
  void optional_attr(const std::string& g, const char* name, const T& v) {
    attr(g, name, v);
  }
  template <class E, class Parse>
  void choice(const std::string& g, const char* name, E v, Parse) {
    f_.set_attribute(g, name, to_string(v));
  }
  template <class E, class Parse>
  void optional_choice(const std::string& g, const char* name, E v, Parse parse) {
    choice(g, name, v, parse);
  }
  // Written for people and other tools; not read back.
  void note(const std::string& g, const char* name, const std::string& text) {
    f_.set_attribute(g, name, text);
  }
  void note(const std::string& g, const char* name, std::size_t v) { attr(g, name, v); }

  void text(const std::string& path, const std::string& v) { f_.write_string(path, v); }
  void strings(const std::string& path, const std::vector<std::string>& v) {
    f_.write_strings(path, v);
  }
  void indices(const std::string& path, const std::vector<std::size_t>& v) {
    f_.write_indices(path, v);
  }
  void vector(const std::string& path, const std::vector<double>& v, const std::string& units) {
    f_.write_vector(path, v, units);
  }
  void vector(const std::string& path, const Eigen::VectorXd& v, const std::string& units) {
    f_.write_vector(path, to_std(v), units);
  }
  void matrix(const std::string& path, const Eigen::MatrixXd& m, const std::string& units) {
    f_.write_matrix(path, m, units);
  }
  // A vector made from `object` by `codec.encode` (read back by codec.decode).
  template <class T, class Codec>
  void encoded_vector(const std::string& path, const T& object, const Codec& codec,
                      const std::string& units) {
    f_.write_vector(path, codec.encode(object), units);
  }
  // One attribute per entry (numbers or texts); `reserved` names are other
  // attributes of the group.
  template <class V>
  void attribute_map(const std::string& g, const std::map<std::string, V>& m,
                     const std::set<std::string>& /*reserved*/ = {}) {
    for (const auto& [name, value] : m) f_.set_attribute(g, name, value);
  }

  // Columns of a list of records, one dataset (or string list) per field.
  template <class Row>
  class Columns {
   public:
    Columns(H5File& f, std::string g, const std::vector<Row>& rows) : f_(f), g_(g), rows_(rows) {}
    template <class T>
    void column(const char* name, T Row::*field, const std::string& units) {
      std::vector<double> v;
      for (const auto& row : rows_) v.push_back(static_cast<double>(row.*field));
      f_.write_vector(g_ + "/" + name, v, units);
    }
    void strings(const char* name, std::string Row::*field) {
      std::vector<std::string> v;
      for (const auto& row : rows_) v.push_back(row.*field);
      f_.write_strings(g_ + "/" + name, v);
    }
    // A list per row, stored as one text joined by `separator` (e.g. "v_x+direction_x").
    void joined_strings(const char* name, std::vector<std::string> Row::*field, char separator) {
      std::vector<std::string> v;
      for (const auto& row : rows_) {
        std::string text;
        for (const auto& part : row.*field)
          text += (text.empty() ? "" : std::string(1, separator)) + part;
        v.push_back(text);
      }
      f_.write_strings(g_ + "/" + name, v);
    }

   private:
    H5File& f_;
    std::string g_;
    const std::vector<Row>& rows_;
  };
  template <class Row>
  Columns<Row> columns(const std::string& g, const std::vector<Row>& rows) {
    return {f_, g, rows};
  }
  // Groups <prefix>0, <prefix>1, ... one per element, each walked by `item`.
  template <class T, class F>
  void numbered_groups(const std::string& prefix, const std::vector<T>& items, F item) {
    for (std::size_t k = 0; k < items.size(); ++k) item(prefix + std::to_string(k), items[k]);
  }
  // Whether an optional part is there (written: it has a value).
  template <class T>
  bool optional_part(const std::string& /*g*/, const std::optional<T>& part) {
    return part.has_value();
  }
  // `present`: whether the part is written; read: whether the group exists.
  bool part(const std::string& /*g*/, bool present) { return present; }
  // Whether the part tagged by attribute <g>/<name> = `tag` is there
  // (written: `part` has a value; the tag itself is a note of the part).
  template <class T>
  bool tagged_part(const std::string&, const char*, const char*, const std::optional<T>& part) {
    return part.has_value();
  }
  void lm_history(const std::string& g, const Summary& s) { write_lm_history(f_, g, s); }
  void provenance(const std::string& g, const Provenance& p) { write_provenance(f_, g, p); }
  void require(bool /*ok*/, const std::string& /*what*/) {}  // checked when reading

 private:
  H5File& f_;
};

class ResultLayoutReader {
 public:
  static constexpr bool reading = true;
  explicit ResultLayoutReader(const H5File& file) : f_(file) {}

  [[noreturn]] void bad(const std::string& what) const {
    throw IoError(f_.path().string() + ": " + what);
  }
  void group(const std::string&) {}
  void attr(const std::string& g, const char* name, std::string& v) {
    v = f_.attribute_string(g, name);
  }
  void attr(const std::string& g, const char* name, double& v) { v = f_.attribute_double(g, name); }
  void attr(const std::string& g, const char* name, std::size_t& v) {
    v = static_cast<std::size_t>(f_.attribute_int(g, name));
  }
  void attr(const std::string& g, const char* name, bool& v) { v = f_.attribute_int(g, name) != 0; }
  template <class T>
  void optional_attr(const std::string& g, const char* name, T& v) {
    if (f_.has_attribute(g, name)) attr(g, name, v);
  }
  template <class E, class Parse>
  void choice(const std::string& g, const char* name, E& v, Parse parse) {
    const std::string text = f_.attribute_string(g, name);
    if (!parse(text, v)) bad(g + ": unknown " + name + " '" + text + "'");
  }
  template <class E, class Parse>
  void optional_choice(const std::string& g, const char* name, E& v, Parse parse) {
    if (f_.has_attribute(g, name)) choice(g, name, v, parse);
  }
  template <class T>
  void note(const std::string&, const char*, const T&) {}

  void text(const std::string& path, std::string& v) { v = f_.read_string(path); }
  void strings(const std::string& path, std::vector<std::string>& v) { v = f_.read_strings(path); }
  void indices(const std::string& path, std::vector<std::size_t>& v) { v = f_.read_indices(path); }
  void vector(const std::string& path, std::vector<double>& v, const std::string&) {
    v = f_.read_vector(path);
  }
  void vector(const std::string& path, Eigen::VectorXd& v, const std::string&) {
    v = to_eigen(f_.read_vector(path));
  }
  void matrix(const std::string& path, Eigen::MatrixXd& m, const std::string&) {
    m = f_.read_matrix(path);
  }
  template <class T, class Codec>
  void encoded_vector(const std::string& path, T& object, const Codec& codec, const std::string&) {
    const std::string error = codec.decode(f_.read_vector(path), object);
    if (!error.empty()) bad(path + ": " + error);
  }
  void attribute_map(const std::string& g, std::map<std::string, double>& m,
                     const std::set<std::string>& reserved = {}) {
    for (const auto& name : f_.attribute_names(g)) {
      if (!reserved.contains(name)) m[name] = f_.attribute_double(g, name);
    }
  }
  void attribute_map(const std::string& g, std::map<std::string, std::string>& m,
                     const std::set<std::string>& reserved = {}) {
    for (const auto& name : f_.attribute_names(g)) {
      if (!reserved.contains(name)) m[name] = f_.attribute_string(g, name);
    }
  }

  // The first column sizes the list; every other must have as many values.
  template <class Row>
  class Columns {
   public:
    Columns(const ResultLayoutReader& io, std::string g, std::vector<Row>& rows)
        : io_(io), g_(g), rows_(rows) {}
    template <class T>
    void column(const char* name, T Row::*field, const std::string&) {
      const auto v = io_.f_.read_vector(g_ + "/" + name);
      size_to(v.size());
      for (std::size_t i = 0; i < v.size(); ++i) rows_[i].*field = static_cast<T>(v[i]);
    }
    void strings(const char* name, std::string Row::*field) {
      const auto v = io_.f_.read_strings(g_ + "/" + name);
      size_to(v.size());
      for (std::size_t i = 0; i < v.size(); ++i) rows_[i].*field = v[i];
    }
    void joined_strings(const char* name, std::vector<std::string> Row::*field, char separator) {
      const auto v = io_.f_.read_strings(g_ + "/" + name);
      size_to(v.size());
      for (std::size_t i = 0; i < v.size(); ++i) {
        auto& parts = rows_[i].*field;
        parts.clear();
        for (std::size_t from = 0;;) {
          const std::size_t at = v[i].find(separator, from);
          parts.push_back(v[i].substr(from, at == std::string::npos ? at : at - from));
          if (at == std::string::npos) break;
          from = at + 1;
        }
      }
    }

   private:
    void size_to(std::size_t n) {
      if (first_) {
        rows_.resize(n);
        first_ = false;
      } else if (n != rows_.size()) {
        io_.bad(g_ + ": series of different lengths");
      }
    }
    const ResultLayoutReader& io_;
    std::string g_;
    std::vector<Row>& rows_;
    bool first_ = true;
  };
  template <class Row>
  Columns<Row> columns(const std::string& g, std::vector<Row>& rows) {
    return {*this, g, rows};
  }
  template <class T, class F>
  void numbered_groups(const std::string& prefix, std::vector<T>& items, F item) {
    for (std::size_t k = 0; f_.exists(prefix + std::to_string(k)); ++k) {
      item(prefix + std::to_string(k), items.emplace_back());
    }
  }
  template <class T>
  bool optional_part(const std::string& g, std::optional<T>& part) {
    if (!f_.is_group(g)) return false;
    part.emplace();
    return true;
  }
  bool part(const std::string& g, bool) { return f_.exists(g); }
  template <class T>
  bool tagged_part(const std::string& g, const char* name, const char* tag,
                   std::optional<T>& part) {
    if (!f_.has_attribute(g, name) || f_.attribute_string(g, name) != tag) return false;
    part.emplace();
    return true;
  }
  void provenance(const std::string& g, Provenance& p) { p = read_provenance(f_, g); }
  void lm_history(const std::string& g, Summary& s) { read_lm_history(f_, g, s.history.size(), s); }
  void require(bool ok, const std::string& what) {
    if (!ok) bad(what);
  }

 private:
  const H5File& f_;
};

}  // namespace cnclab
