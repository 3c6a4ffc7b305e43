#pragma once
// Every registered metrics module's headline lines (sim/evaluator/module/headline.hpp), in
// summary order: what `robodds run`'s report and `robodds sweep`'s stdout table show.

#include "sim/evaluator/module/headline.hpp"

namespace robodds {

evaluator::Headline module_headlines();

}  // namespace robodds
