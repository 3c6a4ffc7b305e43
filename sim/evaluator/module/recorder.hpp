#pragma once
// One recorded topic of the evaluator: its samples go to the callbacks the metrics modules
// attached to the topic (metrics_setup.hpp) as they are taken, and become CSV rows on the
// evaluator's writer thread (runtime/io/batch_writer_thread.hpp).

#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "runtime/base/error.hpp"
#include "runtime/io/batch_writer_thread.hpp"
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
  /// Appends `rows` (whole lines); RunError if the file cannot take them.
  void write(const std::string& rows) {
    if (file_.is_open() && !file_.write(rows.data(), static_cast<std::streamsize>(rows.size()))) {
      throw RunError("evaluator: cannot write " + path_);
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

/// The samples one recorder took at one step, turned into CSV rows on the evaluator's writer
/// thread (the step only takes them and feeds the metrics).
class CsvBatch {
 public:
  explicit CsvBatch(std::size_t stream) : stream_(stream) {}
  virtual ~CsvBatch() = default;
  /// Appends its rows to its file; `text`: the writer thread's buffer, reused from batch to batch.
  virtual void write(std::string& text) = 0;
  /// Forgets the samples, keeps the storage.
  virtual void clear() = 0;
  std::size_t stream() const { return stream_; }

 private:
  std::size_t stream_;
};

/// The evaluator's CSV writer: one thread for every recorder that writes its rows through it.
using CsvWriter = BatchWriterThread<CsvBatch>;

/// Batches (one per recorder and step) that may wait for the CSV writer: ~85 steps of three
/// topics, so that a fast co-located run, whose steps outpace the writer, holds a few MB at most
/// (integration.evaluator_memory).
constexpr std::size_t kMaxQueuedCsvBatches = 4 * CsvWriter::kWakeAt;

/// A CsvWriter whose work is CsvBatch::write.
inline std::unique_ptr<CsvWriter> make_csv_writer() {
  return std::make_unique<CsvWriter>(
      "evaluator", [text = std::string()](CsvBatch& batch) mutable { batch.write(text); }, kMaxQueuedCsvBatches);
}

class RecorderBase {
 public:
  virtual ~RecorderBase() = default;
  /// Creates the CSV file in `dir` and writes its header; `writer`: the thread that may write its
  /// rows (it outlives the recorder's last flush()).
  virtual void open(const std::string& dir, CsvWriter& writer) = 0;
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

/// The samples of a Recorder<Msg> at one step, as CSV rows of `file`.
template <class Msg>
class TypedCsvBatch : public CsvBatch {
 public:
  TypedCsvBatch(std::size_t stream, CsvFile* file) : CsvBatch(stream), file_(file) {}
  std::vector<Msg>& samples() { return samples_; }
  void write(std::string& text) override {
    text.clear();
    for (const Msg& sample : samples_) {
      append_seconds(text, static_cast<std::int64_t>(sample.header().stamp_ns()));
      text += ',';
      append_csv_row(text, sample);
      text += '\n';
    }
    file_->write(text);
  }
  void clear() override { samples_.clear(); }

 private:
  CsvFile* file_;  // the recorder's; written by the writer thread only once opened
  std::vector<Msg> samples_;
};

/// Writes each sample of its topic as a CSV row (not opened: no file). `keys`: the instances it
/// reads, in this order at each step. `by_robot`: a topic keyed (robot_id, target_id) subscribed
/// with Subscription::robot_streams(), `keys` robot ids: each robot's samples, whatever the
/// target, in step order. `callbacks`: called with each sample, in order, when it is taken; the
/// rows are made and written later by the writer thread, in the same order.
template <class Msg>
class Recorder : public TopicRecorder {
 public:
  using Callback = std::function<void(const Msg&)>;
  Recorder(std::string topic, Input<Msg>* input, std::vector<std::uint64_t> keys, bool by_robot = false,
           std::vector<Callback> callbacks = {})
      : TopicRecorder(std::move(topic), input), input_(input), keys_(std::move(keys)), by_robot_(by_robot),
        callbacks_(std::move(callbacks)) {}
  void open(const std::string& dir, CsvWriter& writer) override {
    file_.open(dir, topic_, "t_s," + csv_header<Msg>());
    writer_ = &writer;
    stream_ = writer.add_stream();
  }
  void collect() override {
    if (!batch_) {
      batch_ = std::make_unique<TypedCsvBatch<Msg>>(stream_, &file_);
    }
    std::vector<Msg>& samples = batch_->samples();
    samples.clear();
    // Every key's samples in one call (one lock), in the order of keys_, into a reused buffer.
    if (by_robot_) {
      input_->take_new_of_robots(keys_, samples);
    } else {
      input_->take_new(keys_, samples);
    }
    for (const Msg& sample : samples) {
      ++rows_;
      for (const Callback& callback : callbacks_) {
        callback(sample);
      }
    }
    if (writer_ != nullptr && !samples.empty()) {
      // A written batch of our stream (so one of ours) to fill next, or none yet.
      batch_.reset(static_cast<TypedCsvBatch<Msg>*>(writer_->push(std::move(batch_)).release()));
    }
  }
  /// Every row taken so far in the file.
  void flush() override {
    if (writer_ != nullptr) {
      writer_->drain();
    }
    file_.flush();
  }

 private:
  Input<Msg>* input_;
  std::vector<std::uint64_t> keys_;
  bool by_robot_;
  std::vector<Callback> callbacks_;
  CsvWriter* writer_ = nullptr;  // null until opened (no output: the rows go nowhere)
  std::size_t stream_ = 0;       // its batches' series in writer_
  std::unique_ptr<TypedCsvBatch<Msg>> batch_;  // the one the next collect() fills
};

}  // namespace robodds::evaluator
