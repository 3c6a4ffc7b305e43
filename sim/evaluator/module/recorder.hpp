#pragma once
// One recorded topic of the evaluator: its samples become CSV rows as they are taken and go to
// the callbacks the metrics modules attached to the topic (metrics_setup.hpp).

#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/io/sample_format.hpp"

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

/// The CSV file of one recorder (not opened: the run writes no output, rows go nowhere).
class CsvFile {
 public:
  /// Creates <dir>/<topic with / as _>.csv with the line `header`; RunError if it cannot.
  void open(const std::string& dir, const std::string& topic, const std::string& header) {
    path_ = dir + "/" + csv_file_name(topic);
    file_.open(path_, std::ios::binary | std::ios::trunc);
    file_ << header << '\n';
    if (!file_) {
      throw RunError("evaluator: cannot write " + path_);
    }
  }
  /// Appends `rows` (whole lines).
  void write(const std::string& rows) {
    if (file_.is_open()) {
      file_.write(rows.data(), static_cast<std::streamsize>(rows.size()));
    }
  }
  /// Pushes the rows written so far to the file; RunError if it cannot.
  void flush() {
    if (file_.is_open() && !file_.flush()) {
      throw RunError("evaluator: cannot write " + path_);
    }
  }

 private:
  std::string path_;
  std::ofstream file_;  // buffered: rows reach the disk in blocks, and at flush()
};

class RecorderBase {
 public:
  virtual ~RecorderBase() = default;
  /// Creates the CSV file in `dir` and writes its header.
  virtual void open(const std::string& dir) = 0;
  /// Takes the readable samples of its instances (rows written now, or later by a recorder
  /// whose rows wait for more than the sample).
  virtual void collect() = 0;
  /// Pushes the rows written so far to the file; RunError if it cannot.
  virtual void flush() = 0;
  virtual const std::string& topic() const = 0;
  virtual std::uint64_t rejected() const = 0;
  virtual std::size_t rows() const = 0;
};

/// What every recorder of an input keeps: its topic, the input (for its rejected samples), its
/// CSV file and the rows counted.
class TopicRecorder : public RecorderBase {
 public:
  void flush() override { file_.flush(); }
  const std::string& topic() const override { return topic_; }
  std::uint64_t rejected() const override { return counted_input_->rejected_count(); }
  std::size_t rows() const override { return rows_; }

 protected:
  TopicRecorder(std::string topic, const InputBase* input) : topic_(std::move(topic)), counted_input_(input) {}
  std::string topic_;
  CsvFile file_;
  std::size_t rows_ = 0;  // samples taken

 private:
  const InputBase* counted_input_;  // its rejected samples
};

/// Writes each sample of its topic as a CSV row when it is taken (not opened: no file). `keys`:
/// the instances it reads, in this order at each step. `by_robot`: a topic keyed (robot_id,
/// target_id) subscribed with Subscription::robot_streams(), `keys` robot ids: each robot's
/// samples, whatever the target, in step order. `callbacks`: called with each sample, in order.
template <class Msg>
class Recorder : public TopicRecorder {
 public:
  using Callback = std::function<void(const Msg&)>;
  Recorder(std::string topic, Input<Msg>* input, std::vector<std::uint64_t> keys, bool by_robot = false,
           std::vector<Callback> callbacks = {})
      : TopicRecorder(std::move(topic), input), input_(input), keys_(std::move(keys)), by_robot_(by_robot),
        callbacks_(std::move(callbacks)) {}
  void open(const std::string& dir) override { file_.open(dir, topic_, "t_s," + csv_header<Msg>()); }
  void collect() override {
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
      for (const Callback& callback : callbacks_) {
        callback(sample);
      }
    }
    file_.write(text_);
  }

 private:
  Input<Msg>* input_;
  std::vector<std::uint64_t> keys_;
  bool by_robot_;
  std::vector<Callback> callbacks_;
  std::string text_;    // the rows of one collect()
  std::vector<Msg> samples_;  // the samples of one collect()
};

}  // namespace robodds::evaluator
