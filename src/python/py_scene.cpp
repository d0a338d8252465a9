#include "py_scene.hpp"

#include <stdexcept>

namespace py = pybind11;

namespace ragdoll_sim {
namespace python {

void MessageLog::message(const SceneMessage& m) {
  if (messages.size() >= capacity) messages.erase(messages.begin());
  messages.push_back(m);
  ++total;
}

std::string MessageLog::problemsSince(uint64_t mark) const {
  std::string out;
  const uint64_t kept_from = total - messages.size();
  for (uint64_t i = std::max(mark, kept_from); i < total; ++i) {
    const SceneMessage& m = messages[static_cast<size_t>(i - kept_from)];
    if (m.level != SceneMessage::Level::Warn && m.level != SceneMessage::Level::Error) continue;
    if (!out.empty()) out += "; ";
    out += m.text;
  }
  return out;
}

PyScene::PyScene(SceneDef def) {
  if (def.dt_ns <= 0)
    throw std::invalid_argument("dt must be > 0 s, got " + std::to_string(def.dt_ns) + " ns");
  const std::string bad = worldDefError(def.world);
  if (!bad.empty()) throw std::invalid_argument(bad);
  scene_ = std::make_unique<Scene>(std::move(def), &log_);
  std::string error;
  if (!scene_->start(&error)) throw std::runtime_error("the scene did not start: " + error);
}

int PyScene::index(const std::string& name) const {
  const int k = name.empty() ? -1 : scene_->find(name);
  if (k < 0) {
    std::string known;
    for (size_t i = 0; i < scene_->ragdollCount(); ++i)
      known += (known.empty() ? "" : ", ") + ("'" + scene_->name(static_cast<int>(i)) + "'");
    throw std::invalid_argument("no ragdoll or object named '" + name + "' (the scene has " +
                                (known.empty() ? std::string("none") : known) + ")");
  }
  return k;
}

int PyScene::link(int k, const std::string& link) const {
  const int i = scene_->findLink(k, link);
  if (i < 0)
    throw std::invalid_argument("ragdoll '" + scene_->name(k) + "' has no link '" + link + "'");
  return i;
}

void PyScene::command(const std::string& ragdoll, SceneCommandVariant command) {
  index(ragdoll);
  const uint64_t rejected = scene_->counters().rejected;
  const uint64_t dropped = scene_->counters().dropped;
  const uint64_t mark = log_.total;
  scene_->submit(ragdoll, std::move(command), scene_->timeNs());
  scene_->applyDueCommands();
  const SceneCounters c = scene_->counters();
  if (c.rejected != rejected || c.dropped != dropped) {
    const std::string why = log_.problemsSince(mark);
    throw std::invalid_argument(why.empty() ? "the scene refused the command" : why);
  }
}

void PyScene::step(long n) {
  if (n < 0) throw std::invalid_argument("n must be >= 0, got " + std::to_string(n));
  impacts.clear();
  ended_falls.clear();
  broken.clear();
  // Ctrl-C is looked at between chunks of steps (the GIL is taken back for it).
  constexpr long kChunk = 2000;
  for (long done = 0; done < n;) {
    const long chunk = std::min(kChunk, n - done);
    {
      py::gil_scoped_release release;
      for (long i = 0; i < chunk; ++i) {
        scene_->step();
        const auto& hits = scene_->impacts();
        if (!hits.empty()) impacts.insert(impacts.end(), hits.begin(), hits.end());
        const auto& falls = scene_->injuryReports();
        if (!falls.empty()) ended_falls.insert(ended_falls.end(), falls.begin(), falls.end());
        const auto& joints = scene_->brokenJoints();
        if (!joints.empty()) broken.insert(broken.end(), joints.begin(), joints.end());
      }
    }
    done += chunk;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
}

}  // namespace python
}  // namespace ragdoll_sim
