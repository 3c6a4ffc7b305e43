#include "common/generated_block.hpp"

#include <cstddef>

namespace robodds {
namespace {

struct Span {
  std::size_t first;  // the first character after the begin marker's line
  std::size_t end;    // the end marker
};

Span block_span(const std::string& doc, const BlockMarkers& markers, const std::string& doc_name) {
  const std::string begin_line = markers.begin + "\n";
  const std::size_t begin = doc.find(begin_line);
  const std::size_t end = begin == std::string::npos ? std::string::npos : doc.find(markers.end, begin + begin_line.size());
  if (end == std::string::npos) {
    throw MissingMarkerError(doc_name + ": expected the line '" + markers.begin + "' followed later by '" +
                             markers.end + "' around the generated block");
  }
  return {begin + begin_line.size(), end};
}

}  // namespace

std::string generated_block(const std::string& doc, const BlockMarkers& markers, const std::string& doc_name) {
  const Span span = block_span(doc, markers, doc_name);
  return doc.substr(span.first, span.end - span.first);
}

std::string with_generated_block(const std::string& doc, const BlockMarkers& markers, const std::string& block,
                                 const std::string& doc_name) {
  const Span span = block_span(doc, markers, doc_name);
  return doc.substr(0, span.first) + block + doc.substr(span.end);
}

}  // namespace robodds
