#pragma once
// A generated block inside a hand-written document: the lines between a begin marker line and an
// end marker (e.g. README.md's layout of the component folders). A generator rewrites only the
// block; a drift test compares it with what the generator renders now. Pure: std only.

#include <stdexcept>
#include <string>

namespace robodds {

/// The marker comments around one generated block.
struct BlockMarkers {
  std::string begin;  // a line of its own; the block starts on the next line
  std::string end;    // where the block stops
};

/// A document without its markers, or with the end marker before the begin marker.
class MissingMarkerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The text of `doc` between the markers (without them). Throws MissingMarkerError naming
/// `doc_name` and both markers.
std::string generated_block(const std::string& doc, const BlockMarkers& markers, const std::string& doc_name);

/// `doc` with the text between the markers replaced by `block`; MissingMarkerError as above.
std::string with_generated_block(const std::string& doc, const BlockMarkers& markers, const std::string& block,
                                 const std::string& doc_name);

}  // namespace robodds
