#pragma once
// One recorded topic of the evaluator: its samples become CSV rows as they are taken.

#include <cstdint>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/io/sample_format.hpp"
#include "sim/evaluator/node/sample_metrics.hpp"

namespace robodds::evaluator {

/// <topic with / as _>.csv
inline std::string csv_file_name(std::string topic) {
  for (char& c : topic) {
    if (c == '/') {
      c = '_';
    }
  }
  return topic + ".csv";
}

class RecorderBase {
 public:
  virtual ~RecorderBase() = default;
  /// Creates the CSV file in `dir` and writes its header.
  virtual void open(const std::string& dir) = 0;
  /// Takes the readable samples of its instances (rows written now, or at settle()).
  virtual void collect(Metrics& metrics) = 0;
  /// Called after every recorder's collect() of the step (the step's truth is in `metrics`):
  /// writes the rows that waited for truth; `final`: the run is over, nothing waits any more.
  virtual void settle(Metrics& /*metrics*/, bool /*final*/) {}
  /// The oldest step of truth (Metrics::relative_truth) this recorder may still need.
  virtual std::uint64_t truth_needed_from() const { return std::numeric_limits<std::uint64_t>::max(); }
  /// Pushes the rows written so far to the file; RunError if it cannot.
  virtual void flush() = 0;
  virtual const std::string& topic() const = 0;
  virtual std::uint64_t rejected() const = 0;
  virtual std::size_t rows() const = 0;
};

/// Writes each sample of its topic as a CSV row when it is taken (not opened: no file). `keys`:
/// the instances it reads, in this order at each step. `by_robot`: a topic keyed (robot_id,
/// target_id) subscribed with Subscription::robot_streams(), `keys` robot ids: each robot's
/// samples, whatever the target, in step order.
template <class Msg>
class Recorder : public RecorderBase {
 public:
  Recorder(std::string topic, Input<Msg>* input, std::vector<std::uint64_t> keys, bool by_robot = false)
      : topic_(std::move(topic)), input_(input), keys_(std::move(keys)), by_robot_(by_robot) {}
  void open(const std::string& dir) override {
    path_ = dir + "/" + csv_file_name(topic_);
    file_.open(path_, std::ios::binary | std::ios::trunc);
    file_ << "t_s," << csv_header<Msg>() << '\n';
    if (!file_) {
      throw RunError("evaluator: cannot write " + path_);
    }
  }
  void collect(Metrics& metrics) override {
    text_.clear();
    samples_.clear();
    // Every key's samples in one call (one lock), in the order of keys_, into a reused buffer.
    if (by_robot_) {
      input_->take_new_of_robots(keys_, samples_);
    } else {
      input_->take_new(keys_, samples_);
    }
    for (const Msg& sample : samples_) {
      append_seconds(text_, static_cast<std::int64_t>(sample.header().stamp_ns()));
      text_ += ',';
      append_csv_row(text_, sample);
      text_ += '\n';
      ++rows_;
      metrics.observe(sample, topic_);
    }
    if (file_.is_open()) {
      file_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
    }
  }
  void flush() override {
    if (file_.is_open() && !file_.flush()) {
      throw RunError("evaluator: cannot write " + path_);
    }
  }
  const std::string& topic() const override { return topic_; }
  std::uint64_t rejected() const override { return input_->rejected_count(); }
  std::size_t rows() const override { return rows_; }

 private:
  std::string topic_;
  Input<Msg>* input_;
  std::vector<std::uint64_t> keys_;
  bool by_robot_;
  std::string path_;
  std::ofstream file_;  // buffered: rows reach the disk in blocks, and at flush()
  std::string text_;    // the rows of one collect()
  std::vector<Msg> samples_;  // the samples of one collect()
  std::size_t rows_ = 0;
};

}  // namespace robodds::evaluator
