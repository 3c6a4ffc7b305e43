#include "common/model/target_plan.hpp"

#include <algorithm>
#include <cmath>

namespace robodds::model {

std::uint64_t TargetPlan::event_step(double time_s, double step_s) {
  return static_cast<std::uint64_t>(std::llround(time_s / step_s));
}

std::vector<std::uint64_t> TargetPlan::change_steps(double step_s) const {
  std::vector<std::uint64_t> steps;
  for (const TargetEvent& e : events) {
    steps.push_back(event_step(e.time_s, step_s));
  }
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  return steps;
}

const Target* TargetPlan::target(std::uint32_t id) const {
  for (const Target& t : targets) {
    if (t.id == id) {
      return &t;
    }
  }
  return nullptr;
}

std::map<std::uint32_t, RobotTask> TargetPlan::tasks_at(std::uint64_t step, double step_s,
                                                        const std::vector<std::uint32_t>& robots) const {
  std::map<std::uint32_t, RobotTask> tasks;
  for (std::uint32_t id : robots) {
    tasks[id] = RobotTask{};
  }
  for (const TargetEvent& e : events) {
    if (event_step(e.time_s, step_s) > step) {
      break;  // events are in time order
    }
    for (std::uint32_t id : e.robots) {
      auto it = tasks.find(id);
      if (it == tasks.end()) {
        continue;  // not a listed robot
      }
      RobotTask& task = it->second;
      const Target* t = e.leave ? nullptr : target(e.target_id);
      task = RobotTask{};
      if (t != nullptr) {
        task.active = true;
        task.target_id = t->id;
        task.target_x = t->x;
        task.target_y = t->y;
        task.radius_m = t->radius_m;
      }
    }
  }
  // Teams: the active robots of one target, ranked by id (the map's order).
  std::map<std::uint32_t, std::uint32_t> team_sizes;
  for (auto& [id, task] : tasks) {
    if (task.active) {
      task.slot = team_sizes[task.target_id]++;
    }
  }
  for (auto& [id, task] : tasks) {
    if (task.active) {
      task.team_size = team_sizes[task.target_id];
    }
  }
  return tasks;
}

}  // namespace robodds::model
