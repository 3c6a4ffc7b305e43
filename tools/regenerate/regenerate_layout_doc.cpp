// regenerate_layout_doc README.md: rewrites the generated rows of the README's Layout (the
// component folders and the evaluator's metrics modules) from their registration. Run through
// scripts/regenerate_layout_doc.sh after adding, moving or describing a component or module.

#include "tools/regenerate/generated_block_main.hpp"
#include "tools/regenerate/layout_table.hpp"
#include "tools/regenerate/registered_layout_table.hpp"

int main(int argc, char** argv) {
  return robodds::generated_block_main(argc, argv,
                                       {"regenerate_layout_doc", "layout rows",
                                        "the registered components and metrics modules", robodds::kLayoutTableMarkers,
                                        robodds::render_registered_layout_table});
}
