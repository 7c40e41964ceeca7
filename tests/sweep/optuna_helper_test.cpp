// The Optuna helper's protocol as the C++ side sees it: a study round trip,
// bad messages answered without ending the helper, a helper that dies or
// hangs (a clear error within the timeout, no hang), a Python without Optuna
// (ConfigError naming python3-optuna), and fANOVA importance: a dummy
// parameter that provably does not change the objective ranks lowest, and
// the helper's numbers equal Optuna's own evaluation of the same journal
// (computed by a separate Python process, not by our code).
#include "cnclab/sweep/optuna_helper.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::TempDir;

const fs::path kScript = CNCLAB_SOURCE_DIR "/scripts/optuna/optuna_helper.py";

OptunaHelperOptions options(double timeout = 300) {
  OptunaHelperOptions o;
  o.script = kScript;
  o.timeout_seconds = timeout;
  return o;
}

json open_message(const fs::path& journal) {
  return {{"op", "open"},
          {"journal", journal.string()},
          {"directions", {"minimize"}},
          {"sampler", {{"name", "tpe"}, {"seed", 7}}},
          {"pruner", {{"name", "median"}, {"n_startup_trials", 1}}},
          {"params",
           {{{"name", "lr"}, {"type", "float"}, {"low", 1e-4}, {"high", 1e-1}, {"log", true}},
            {{"name", "x"}, {"type", "float"}, {"low", 0.0}, {"high", 1.0}},
            {{"name", "dummy"}, {"type", "categorical"}, {"choices", {"a", "b", "c"}}}}},
          {"holder", {{"host", "testhost"}, {"pid", 1}}}};
}

fs::path write_script(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  fs::permissions(p, fs::perms::owner_all);
  return p;
}

TEST(OptunaHelper, StudyRoundTripAndBadMessages) {
  TempDir tmp;
  OptunaHelper h(options());
  EXPECT_THROW(h.request({{"op", "ask"}}), Error);  // no study yet
  h.request(open_message(tmp.path() / "study.journal"));
  // Malformed lines and unknown ops are answered with an error; the helper goes on.
  EXPECT_FALSE(h.request_line("not json").value("ok", true));
  EXPECT_FALSE(h.request_line("[1, 2]").value("ok", true));
  EXPECT_FALSE(h.request_line(R"({"op": "fly"})").value("ok", true));
  EXPECT_FALSE(
      h.request_line(R"({"op": "report", "number": 99, "step": 1, "value": 1})").value("ok", true));
  const json a = h.request({{"op", "ask"}, {"limit", 2}});
  const long long n = a.at("number").get<long long>();
  EXPECT_GE(a.at("params").at("lr").get<double>(), 1e-4);
  EXPECT_LE(a.at("params").at("lr").get<double>(), 1e-1);
  EXPECT_FALSE(h.request_line(R"({"op": "report", "number": )" + std::to_string(n) +
                              R"(, "step": -1, "value": 1})")
                   .value("ok", true));
  EXPECT_FALSE(h.request({{"op", "report"}, {"number", n}, {"step", 1}, {"value", 0.5}})
                   .value("prune", true));  // the first trial is never pruned (startup)
  // A complete trial needs a finite value (JSON null is NaN).
  EXPECT_THROW(
      h.request({{"op", "tell"}, {"number", n}, {"state", "complete"}, {"values", {nullptr}}}),
      Error);
  EXPECT_THROW(h.request({{"op", "tell"}, {"number", n}, {"state", "done"}}), Error);
  h.request({{"op", "tell"}, {"number", n}, {"state", "complete"}, {"values", {0.25}}});
  const json b = h.request({{"op", "ask"}, {"limit", 2}});
  h.request({{"op", "tell"}, {"number", b.at("number")}, {"state", "pruned"}});
  // The limit counts complete and pruned trials: nothing more to ask.
  EXPECT_TRUE(h.request({{"op", "ask"}, {"limit", 2}}).at("number").is_null());
  const json c = h.request({{"op", "count"}});
  EXPECT_EQ(c.at("complete"), 1);
  EXPECT_EQ(c.at("pruned"), 1);
  EXPECT_EQ(c.at("running"), 0);
}

TEST(OptunaHelper, StudyContinuesFromItsJournal) {
  TempDir tmp;
  const fs::path journal = tmp.path() / "study.journal";
  {
    OptunaHelper h(options());
    h.request(open_message(journal));
    const json a = h.request({{"op", "ask"}, {"limit", 3}});
    h.request(
        {{"op", "tell"}, {"number", a.at("number")}, {"state", "complete"}, {"values", {1.0}}});
  }
  OptunaHelper h(options());
  h.request(open_message(journal));
  EXPECT_EQ(h.request({{"op", "ask"}, {"limit", 3}}).at("number"), 1);
}

// Trials held by a process of this host that has ended are failed when a
// worker opens the study (the lock-file rule), and asked again.
TEST(OptunaHelper, DeadHoldersTrialsAreFailedOnOpen) {
  TempDir tmp;
  const fs::path journal = tmp.path() / "study.journal";
  const std::string host = [] {
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    return std::string(name);
  }();
  const pid_t gone = [] {
    const pid_t p = ::fork();
    if (p == 0) ::_exit(0);
    ::waitpid(p, nullptr, 0);
    return p;  // reaped: no such process now
  }();
  {
    OptunaHelper h(options());
    json m = open_message(journal);
    m["holder"] = {{"host", host}, {"pid", gone}};
    h.request(m);
    h.request({{"op", "ask"}, {"limit", 5}});  // left running
  }
  OptunaHelper h(options());
  json m = open_message(journal);
  m["holder"] = {{"host", host}, {"pid", ::getpid()}};
  const json opened = h.request(m);
  ASSERT_EQ(opened.at("reaped").size(), 1u);
  EXPECT_EQ(h.request({{"op", "count"}}).at("failed"), 1);
}

TEST(OptunaHelper, HelperThatDiesIsAClearErrorNotAHang) {
  TempDir tmp;
  // Answers hello, then dies on the next message with a note on stderr.
  OptunaHelperOptions o = options(20);
  o.script = write_script(tmp.path(), "dies.py",
                          "import sys\n"
                          "sys.stdin.readline(); print('{\"ok\": true}', flush=True)\n"
                          "sys.stdin.readline(); sys.stderr.write('boom: out of luck\\n')\n"
                          "sys.exit(3)\n");
  OptunaHelper h(o);
  const auto start = std::chrono::steady_clock::now();
  try {
    h.request({{"op", "count"}});
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("exited with status 3"), std::string::npos) << what;
    EXPECT_NE(what.find("boom: out of luck"), std::string::npos) << what;
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(15));
  // Later requests fail at once too (its socket is closed).
  EXPECT_THROW(h.request({{"op", "count"}}), Error);
}

TEST(OptunaHelper, HelperThatHangsTimesOut) {
  TempDir tmp;
  OptunaHelperOptions o = options(2);
  o.script = write_script(tmp.path(), "hangs.py",
                          "import sys, time\n"
                          "sys.stdin.readline(); print('{\"ok\": true}', flush=True)\n"
                          "time.sleep(600)\n");
  OptunaHelper h(o);
  const auto start = std::chrono::steady_clock::now();
  try {
    h.request({{"op", "count"}});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no answer within"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(OptunaHelper, GarbageAnswerIsAnError) {
  TempDir tmp;
  OptunaHelperOptions o = options(20);
  o.script = write_script(tmp.path(), "garbage.py",
                          "import sys\n"
                          "sys.stdin.readline(); print('{\"ok\": true}', flush=True)\n"
                          "sys.stdin.readline(); print('surprise', flush=True)\n"
                          "sys.stdin.read()\n");
  OptunaHelper h(o);
  EXPECT_THROW(h.request({{"op", "count"}}), Error);
}

TEST(OptunaHelper, PythonWithoutOptunaNamesThePackage) {
  TempDir tmp;
  // The system Python without its site packages (-S) cannot import optuna.
  OptunaHelperOptions o = options();
  o.interpreter = write_script(tmp.path(), "python-without-site",
                               "#!/bin/sh\nexec /usr/bin/python3 -S \"$@\"\n");
  o.purpose = "sweep method tpe";
  try {
    OptunaHelper h(o);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("python3-optuna"), std::string::npos) << what;
    EXPECT_NE(what.find("sweep method tpe"), std::string::npos) << what;
  }
  o.interpreter = tmp.path() / "no-such-python";
  EXPECT_THROW(OptunaHelper{o}, ConfigError);
}

TEST(OptunaHelper, DummyParameterHasTheLowestImportance) {
  TempDir tmp;
  const fs::path journal = tmp.path() / "study.journal";
  OptunaHelper h(options());
  json m = open_message(journal);
  m["pruner"] = {{"name", "none"}};
  h.request(m);
  // f depends on lr and x only; dummy never enters it.
  for (int i = 0; i < 40; ++i) {
    const json a = h.request({{"op", "ask"}, {"limit", 40}});
    const double lr = a.at("params").at("lr"), x = a.at("params").at("x");
    const double f = std::pow(std::log10(lr) + 2.0, 2) + 0.3 * std::pow(x - 0.5, 2);
    h.request({{"op", "tell"}, {"number", a.at("number")}, {"state", "complete"}, {"values", {f}}});
  }
  const json imp = h.request({{"op", "importance"}});
  const auto names = imp.at("parameter").get<std::vector<std::string>>();
  const auto values = imp.at("value").get<std::vector<double>>();
  ASSERT_EQ(names.size(), 3u);
  EXPECT_EQ(names.front(), "lr");
  EXPECT_EQ(names.back(), "dummy");
  for (std::size_t i = 1; i < values.size(); ++i) EXPECT_GE(values[i - 1], values[i]);

  // Optuna itself on the same journal, in its own process.
  const auto r = testing::run_shell(
      tmp.path(),
      "/usr/bin/python3 -c \"import optuna, warnings; warnings.simplefilter('ignore');"
      "from optuna.storages import JournalStorage, JournalFileStorage as F;"
      "s = optuna.load_study(study_name='cnclab', storage=JournalStorage(F('" +
          journal.string() +
          "')));"
          "imp = optuna.importance.get_param_importances(s, "
          "evaluator=optuna.importance.FanovaImportanceEvaluator(seed=0));"
          "print(' '.join('%s=%.17g' % kv for kv in imp.items()))\"");
  ASSERT_EQ(r.code, 0) << r.err;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto at = r.out.find(names[i] + "=");
    ASSERT_NE(at, std::string::npos) << r.out;
    EXPECT_NEAR(std::stod(r.out.substr(at + names[i].size() + 1)), values[i], 1e-12);
  }
}

// The sweep block's sampler options reach Optuna: the helper's trials equal
// those of Optuna's own TPESampler built with the same options and seed and
// told the same values (a separate Python process), and differ from the
// default sampler's after the shorter start-up. Unknown options and wrong
// types are errors naming the option.
TEST(OptunaHelper, SamplerOptionsReachOptuna) {
  TempDir tmp;
  const auto f = [](double lr, double x) {
    return std::pow(std::log10(lr) + 2.0, 2) + 0.3 * std::pow(x - 0.5, 2);
  };
  constexpr int kTrials = 8;
  OptunaHelper h(options());
  json m = open_message(tmp.path() / "study.journal");
  m["pruner"] = {{"name", "none"}};
  m["sampler"]["options"] = {{"n_startup_trials", 3}, {"multivariate", true}};
  h.request(m);
  std::vector<double> ours;
  for (int i = 0; i < kTrials; ++i) {
    const json a = h.request({{"op", "ask"}, {"limit", kTrials}});
    const double lr = a.at("params").at("lr"), x = a.at("params").at("x");
    ours.insert(ours.end(), {lr, x});
    h.request({{"op", "tell"},
               {"number", a.at("number")},
               {"state", "complete"},
               {"values", {f(lr, x)}}});
  }
  // Optuna alone: the same space, seed and values; argv[1]: the options.
  write_script(tmp.path(), "reference.py", R"py(import math, sys, warnings
import optuna
warnings.simplefilter("ignore")
D = optuna.distributions
space = {"lr": D.FloatDistribution(1e-4, 1e-1, log=True), "x": D.FloatDistribution(0.0, 1.0),
         "dummy": D.CategoricalDistribution(["a", "b", "c"])}
study = optuna.create_study(
    sampler=optuna.samplers.TPESampler(seed=7, **eval("dict(%s)" % sys.argv[1])))
out = []
for i in range(int(sys.argv[2])):
    t = study.ask(space)
    lr, x = t.params["lr"], t.params["x"]
    out += [lr, x]
    study.tell(t, (math.log10(lr) + 2) ** 2 + 0.3 * (x - 0.5) ** 2)
print(" ".join("%.17g" % v for v in out))
)py");
  const auto reference = [&](const std::string& sampler_options) {
    const auto r =
        testing::run_shell(tmp.path(), "/usr/bin/python3 reference.py '" + sampler_options + "' " +
                                           std::to_string(kTrials));
    EXPECT_EQ(r.code, 0) << r.err;
    std::vector<double> v;
    std::istringstream in(r.out);
    for (double x; in >> x;) v.push_back(x);
    return v;
  };
  const std::vector<double> same = reference("n_startup_trials=3, multivariate=True");
  ASSERT_EQ(same.size(), ours.size());
  for (std::size_t i = 0; i < ours.size(); ++i) EXPECT_NEAR(ours[i], same[i], 1e-12 * same[i]);
  const std::vector<double> defaults = reference("");
  ASSERT_EQ(defaults.size(), ours.size());
  EXPECT_NE(std::vector<double>(ours.begin() + 6, ours.end()),
            std::vector<double>(defaults.begin() + 6, defaults.end()));

  for (const auto& [bad_options, named] : std::vector<std::pair<json, std::string>>{
           {{{"multivariat", true}}, "multivariat"},
           {{{"multivariate", "yes"}}, "multivariate"},
           {{{"n_startup_trials", 2.5}}, "n_startup_trials"},
           {{{"n_startup_trials", true}}, "n_startup_trials"}}) {
    OptunaHelper bad(options());
    json b = open_message(tmp.path() / ("bad-" + named + ".journal"));
    b["sampler"]["options"] = bad_options;
    try {
      bad.request(b);
      ADD_FAILURE() << "no error for " << bad_options.dump();
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace cnclab
