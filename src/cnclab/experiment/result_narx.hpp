#pragma once
// The parts of a result file (result_file.hpp) that differ for a narx run
// (model.type narx): its networks, their stages' histories and the
// closed-loop validation prediction. Layout:
//   /model                       attrs type = "narx", hidden, activation,
//                                input_delays, feedback_delays,
//                                first_input_delay, parameter_layout
//   /model/networks              axis names (e_x -> x), one network each
//   /model/inputs, /model/targets   each network's dataset columns
//   /model/<axis>/parameters     its flat parameter vector (nn/narx.hpp)
//   /training                    attrs trainer (the stages, e.g.
//                                "open_loop:trainbr+closed_loop:trainbr"),
//                                termination and message (every stage's)
//   /history/<axis>/stage<k>/    attrs mode, horizon (closed_loop windows;
//                                0 or absent: the whole series), fallback
//                                (1: a second try of the stage before it,
//                                fallback_horizon), trainer,
//                                termination, message,
//                                best_epoch, beta_guard_count, seconds (the
//                                network's); the series of an MLP run's
//                                /history (epoch, train_loss, ..., gradient)
//   /validation/predictions      networks x validation steps, closed loop, in
//                                the dataset's target units; attr first_step:
//                                the leading steps are measured initial states
//   /validation/targets          the measured values
#include <ostream>

#include "cnclab/experiment/run_record.hpp"
#include "cnclab/io/h5.hpp"

namespace cnclab {

void write_narx_sections(H5File& f, const RunRecord& r);
// IoError naming the file and object on a malformed part.
void read_narx_sections(const H5File& f, RunRecord& r);
// The model and training lines of `cnclab show`.
void print_narx_model(const RunRecord& r, std::ostream& out);

}  // namespace cnclab
