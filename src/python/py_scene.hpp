// PyScene: what ragdoll_sim.Scene holds: a started Scene, the log of its messages, and the
// reports of the steps of the last step(n) call (the Scene keeps only the last step's).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {
namespace python {

// The Scene's messages, newest last, at most `capacity` (the oldest go first).
struct MessageLog : SceneListener {
  std::vector<SceneMessage> messages;
  size_t capacity = 1000;
  uint64_t total = 0;  // ever logged: a mark that survives trimming
  void message(const SceneMessage& m) override;
  // The warnings and errors logged since `mark` (a former `total`), joined by "; ".
  std::string problemsSince(uint64_t mark) const;
};

class PyScene {
 public:
  // Builds and starts the Scene; std::invalid_argument when the settings are refused.
  explicit PyScene(SceneDef def);
  Scene& scene() { return *scene_; }
  const Scene& scene() const { return *scene_; }
  MessageLog& log() { return log_; }

  // Index of ragdoll or dynamic object `name`; std::invalid_argument naming it when unknown.
  int index(const std::string& name) const;
  // Index of `link` in ragdoll k; std::invalid_argument naming both when unknown.
  int link(int k, const std::string& link) const;
  // Submits `command` for `ragdoll` due now and applies it; std::invalid_argument carrying the
  // Scene's warning when it is refused.
  void command(const std::string& ragdoll, SceneCommandVariant command);
  // n steps, the GIL released; keeps the impacts, ended falls and broken joints of all of them.
  void step(long n);

  std::vector<ImpactEvent> impacts;         // of the last step(n) call
  std::vector<InjuryReport> ended_falls;    // of the last step(n) call
  std::vector<BrokenJointReport> broken;    // of the last step(n) call

 private:
  MessageLog log_;  // before scene_: the Scene calls it until its end
  std::unique_ptr<Scene> scene_;
};

// The class's methods, one concern per file.
void bindSceneSetup(pybind11::class_<PyScene>& cls);     // bind_scene.cpp: worlds, models, spawn
void bindSceneCommands(pybind11::class_<PyScene>& cls);  // bind_commands.cpp
void bindSceneReports(pybind11::class_<PyScene>& cls);   // bind_reports.cpp
void bindInjury(pybind11::module_& m);                   // bind_reports.cpp: InjuryReport
void bindModel(pybind11::module_& m);                    // bind_model.cpp: Model

}  // namespace python
}  // namespace ragdoll_sim
