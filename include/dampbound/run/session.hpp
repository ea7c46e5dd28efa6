#pragma once
// A running experiment: a scene's model, its state, the parameters, the trace and the verdict.
// The GUI, `run`, `figure` and `check` all drive a Session, and a Session calls the one step().
#include "dampbound/physics/export.hpp"
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dampbound/run/protocol.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound DAMPBOUND_API {

class SettleProof;

/// `scene` as a run of it has it at `iteration`, with `model`'s springs (the cuts made so
/// far): the scene's cuts not reached yet, everything else as loaded (Session::current_scene).
SceneSpec scene_as_run(const SceneSpec& scene, const ModelSpec& model, int iteration);

/// What makes stop rules unusable, naming the rule as the scene files do ("max_iterations must
/// be in 1..100000000", "reference must be > 0"); nullopt when usable.
std::optional<std::string> validate(const StopRules& rules);

class Session {
 public:
  /// Starts from the scene's perturbed state with the given parameters and stop rules.
  /// Throws InputError naming what validate() refuses in the scene, params or rules.
  Session(SceneSpec scene, const Params& params, const StopRules& rules);
  /// Starts with the scene's own parameters and stop rules.
  explicit Session(SceneSpec scene);

  /// One step: applies the scene's cuts due at this iteration, calls step(), records its
  /// stats and the watched node's values in the trace and updates the result. The first
  /// non-running verdict is latched.
  const StepSample& step_once();

  /// Under the settled rule a run may be judged `settled` before its limit where SPEC 8's
  /// proof (docs/settled.md) shows that no later iteration can leave the band; its
  /// `iterations` is then the iteration of the proof.
  ///
  /// Steps until the verdict is no longer running; returns the result.
  const RunResult& run_to_end(const StepObserver& on_step = {});

  /// New parameters take effect at the next step (the model is compiled again); the state
  /// and any cuts are kept. Throws InputError naming the parameter when validate() refuses.
  void set_params(const Params& params);
  void set_rules(const StopRules& rules) { rules_ = rules; }
  /// SPEC 8's early stop (on by default): off, a settled run steps to its limit, so that its
  /// final displacement and counts are those at the limit (`check`'s expectations on them).
  void set_early_stop(bool on);
  /// Threads for step()'s per-node loops (1 by default, 0 = one per hardware thread): the
  /// trajectory is the same bits on any count; meshes of 100k nodes and more gain from it.
  void set_threads(int threads) { ws_.pass.threads.set_threads(threads); }
  /// Watch another node (an index); the trace keeps what was watched before.
  void set_watched(int node);
  /// Back to the scene's topology (cuts undone) and perturbed state; clears trace and result.
  void reset();
  /// Applies the scene's perturbation again on top of the current state.
  void perturb();
  /// Moves one node by hand (the GUI's drag); velocities are kept.
  void displace(int node, const Vec3& offset);
  /// Removes springs now (a cut); bounds react at the next step. Returns how many.
  int cut(const std::vector<int>& springs);

  const SceneSpec& scene() const { return *scene_; }
  /// The scene as loaded, shared (it never changes in a session): what a worker thread takes
  /// instead of a copy.
  std::shared_ptr<const SceneSpec> shared_scene() const { return scene_; }
  /// The scene as this run has it now: its springs as cut so far (from the scene's own cuts
  /// or by hand), the scene's cuts not reached yet, everything else as loaded. What a
  /// suggestion or a fresh run for "this mesh" starts from. Copies the mesh; a worker can
  /// build it from shared_scene() and shared_model() with scene_as_run().
  SceneSpec current_scene() const;
  const Model& model() const { return *model_; }
  /// The same model, shared and never changed again: what a worker thread reads while the run
  /// goes on, without a copy. A later parameter change refills the model in place only when
  /// no one else holds it and otherwise gives the session a copy, so a snapshot keeps the
  /// values it was taken with; a cut or a reset gives the session a new model.
  std::shared_ptr<const Model> shared_model() const { return model_; }
  const State& state() const { return state_; }
  const StepWorkspace& workspace() const { return ws_; }
  const Params& params() const { return params_; }
  const StopRules& rules() const { return rules_; }
  int watched() const { return watched_; }
  /// Every step's stats since the last reset, or only the last step's after
  /// set_keep_trace(false).
  const std::vector<StepSample>& trace() const { return trace_; }
  /// Whether trace() keeps every step (about 100 bytes each: 10 GB for 1e8 iterations) or
  /// only the last; a run that writes no trace keeps only the last.
  void set_keep_trace(bool keep) { keep_trace_ = keep; }
  const RunResult& result() const { return result_; }
  bool running() const { return result_.outcome == Outcome::running; }
  /// Springs removed by cuts since the last reset.
  int springs_cut() const { return springs_cut_; }

 private:
  std::shared_ptr<const SceneSpec> scene_;
  Params params_;
  StopRules rules_;
  std::shared_ptr<Model> model_;  // never null after construction
  State state_;
  StepWorkspace ws_;
  int watched_ = 0;
  std::vector<StepSample> trace_;
  RunResult result_;
  int springs_cut_ = 0;
  bool keep_trace_ = true;
  /// SPEC 8's early stop for the model as it is now (core/run/settle_proof.hpp), rebuilt with
  /// the model; null where the proof's switch is off.
  std::shared_ptr<const SettleProof> settle_;
  int settle_next_ = 0;  ///< the proof's next look (settle::early_verdict)
  bool early_stop_ = true;
  void rebuild_settle();
};

}  // namespace dampbound
