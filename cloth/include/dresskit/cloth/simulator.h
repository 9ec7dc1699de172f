#pragma once
// The spring-mass cloth simulator: state in arrays (#V×3 positions and velocities), a step that reads
// as named phases (integrator, constraints, sewing, collisions), and four time integrators behind
// one interface (cloth/src/integrator.h), each in its own file with its own options: symplectic
// Euler, implicit (backward) Euler with one sparse linear solve per step, Newton's method with line
// search on backward Euler's incremental potential (stiff-robust), and projective dynamics (the
// default).
#include <Eigen/Sparse>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/cloth/collider.h"
#include "dresskit/cloth/self_collision.h"

namespace dresskit::cloth {

enum class Integrator { symplectic_euler, implicit_euler, newton, projective };
enum class LinearSolver { conjugate_gradient, ldlt };
/// Time discretisation of projective dynamics: backward Euler (first order), BDF2 (second order),
/// the implicit midpoint rule (second order, no numerical damping) or TR-BDF2 (second order,
/// L-stable: a midpoint stage over γ h, γ = 2 − √2, then BDF2 over the rest; docs/cloth.md).
enum class TimeScheme { backward_euler, bdf2, midpoint, tr_bdf2 };
/// "backward_euler", "bdf2", "midpoint", "tr_bdf2"; throws InputError naming the value otherwise.
TimeScheme parse_time_scheme(const std::string& text);
std::string to_string(TimeScheme scheme);
/// "symplectic", "implicit", "newton", "projective"; throws InputError naming the value otherwise.
Integrator parse_integrator(const std::string& text);
std::string to_string(Integrator integrator);

/// The linear solves of implicit Euler and Newton.
struct LinearSolveOptions {
  LinearSolver solver = LinearSolver::conjugate_gradient;
  /// Relative residual of the conjugate gradient solve. The error against run time bench found the
  /// time step, not the solve, to set the error: 1e-3 and 1e-8 gave the same error, 1e-3 at a third
  /// of the cost (docs/results.md); 1e-4 keeps a margin.
  double cg_tolerance = 1e-4;
  int cg_max_iterations = 1000;
};

/// Newton's method on backward Euler's incremental potential.
struct NewtonOptions {
  int iterations = 10;  ///< per step at most
};

/// Projective dynamics (projective.cpp).
struct ProjectiveOptions {
  /// Local/global iterations per step at most (fewer when no particle moves more than
  /// SimulationOptions::iteration_tolerance in one).
  int iterations = 10;
  /// Backward Euler's numerical damping sets the error of swinging cloth at large steps; BDF2 (the
  /// same minimisation with inertia target (4x_n − x_{n−1})/3 + (2h/3)(4v_n − v_{n−1})/3 and step
  /// 2h/3) is second order (docs/cloth.md, docs/results.md).
  TimeScheme time_scheme = TimeScheme::backward_euler;
  /// Solve the global step's corrections with a single-precision factor (half the memory traffic;
  /// the double-precision residual keeps the result accurate). false: a double-precision factor
  /// solves for the positions directly.
  bool single_precision = true;
  /// Contacts inside the iterations. Each particle in contact carries a normal contact force in the
  /// global step's right-hand side, raised by the particle's penetration after every global step
  /// (and lowered by its gap once it lifts off), kept from step to step; the particle is also pushed
  /// out to the margin. So the springs are solved around the contacts within the step instead of
  /// being pulled into the collider and pushed back after it (docs/cloth.md). false: contacts only
  /// in the collider pass after the step.
  bool collisions = true;
  /// 0 = local/global iterations; m > 0 = L-BFGS with the last m pairs and the projective matrix as
  /// initial Hessian, with a line search (Liu et al. 2017; docs/cloth.md).
  int lbfgs_history = 0;
  /// Each spring's weight follows its strain (the law's tangent stiffness a little beyond it, raised
  /// and refactorised when a spring stiffens past it) instead of one weight per spring from the
  /// law's knee (docs/cloth.md).
  bool adaptive_weights = false;
};

struct SimulationOptions {
  /// The defaults hold on every scene of the drop matrix (docs/benchmarks.md: cloth dropped onto real
  /// bodies from up to 3.5 m, every fabric, any units): projective dynamics at up to 1/120 s with
  /// adaptive steps, strain limited to 10 %.
  Integrator integrator = Integrator::projective;
  double dt = 1.0 / 120.0;                   ///< time step [s], > 0 (the largest, with adaptive stepping)
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  ///< [m/s²]
  double air_damping = 0.1;     ///< c in f = −c m (v − wind) [1/s]: mass-proportional, resolution independent
  Eigen::Vector3d wind = Eigen::Vector3d::Zero();  ///< air velocity [m/s], acts through air_damping
  double gust_amplitude = 0.0;  ///< wind(t) = wind (1 + a sin 2π f t) [unitless]
  double gust_frequency = 0.0;  ///< f [Hz]
  std::vector<Collider> colliders;
  double collision_margin = 0.002;  ///< particles are kept this far outside colliders [m]
  /// δ of the colliders' penalty force (Collider::penalty): it acts within δ beyond the margin and
  /// grows as exp(depth / δ) (capped at depth 4δ) [m].
  double penalty_thickness = 0.002;
  /// Several layers on analytic colliders: before the length limits and collisions, a particle that
  /// lies less than its layer's min gap (ClothModel::layer_min_gap) above the particle beneath it
  /// (cloth/layers.h, match_layers) is moved out along its nearest collider's normal (at most a tenth of the mean
  /// spring length per step), inner layers first, and loses its inward speed. Only without
  /// cloth–cloth collisions (self_collision off): with them no layer passes through another, and
  /// the guard's pushes made hems wrap around the next garment's (docs/cloth.md, Layers).
  bool layer_order_guard = true;
  /// Cloth–cloth collisions (self-contact, layers, garments; cloth/self_collision.h) after the
  /// collider pass, so that a state without intersections never gains one.
  bool self_collision = false;
  SelfCollisionOptions self_collision_options;
  /// A stitch (ClothModel::seams) that comes within this distance is sewn: from then on the
  /// constraint phase holds its two points together [m].
  double seam_tolerance = 0.001;
  /// Stitches not yet sewn are also drawn together in the constraint phase, each side by half this
  /// speed × dt per step towards where the two are to meet: their midpoint, or, where that lies in a
  /// collider, the nearest way around it (0: by their seam forces alone) [m/s]. The moves count in
  /// the particles' velocities, so the cloth around a stitch follows it.
  double seam_closing_speed = 0.0;
  double spring_damping = 0.0;  ///< β in kd = β k_rest along each spring [s] (Rayleigh stiffness damping)
  bool dynamic_stiffness = false;  ///< k·L/L0 beyond (1 + strain_limit) L0
  bool strain_limiting = true;     ///< position correction after each step
  double strain_limit = 0.1;       ///< largest spring strain allowed by both mechanisms [unitless]
  int strain_limit_iterations = 100;  ///< cap on Gauss–Seidel sweeps of the correction
  double strain_limit_tolerance = 1e-4;  ///< springs within limit + this strain count as done
  /// Each integrator's own options.
  LinearSolveOptions linear;
  NewtonOptions newton;
  ProjectiveOptions projective;
  /// Newton's and projective dynamics' iterations stop when no particle moves more [m].
  double iteration_tolerance = 1e-6;
  double blow_up_strain = 1.0;     ///< a step that leaves a spring strained beyond this has failed
  /// Adaptive time step: a failed step, or one whose integrator raises the largest strain by more
  /// than max_strain_change, is undone and retried at half the step (down to dt_min; a rise that two
  /// halvings did not shrink by a fifth is not the step's doing and is kept); after 10 calm steps
  /// (change below a quarter of that) the step doubles back up to dt. A step is also never longer
  /// than the contact and stability bound (contact_travel; symplectic Euler's limit from the
  /// stiffest spring and the lightest particle). Steps are dt / 2^k.
  bool adaptive = true;
  double dt_min = 1e-6;            ///< [s]
  double max_strain_change = 0.05; ///< per step [unitless]
  /// Leave the springs held at the length limit when a step starts (strain from 0.001 below
  /// strain_limit up, with strain limiting on) out of that rise. The integrator pulls such a spring
  /// towards its elastic rest beyond the limit, and the length limit takes it back, at every step,
  /// by an amount that halving the step shrinks little: where a garment holds springs so for good
  /// (a pattern whose seams join edges of unequal length), their rise of about 0.02 a step keeps
  /// every step from counting calm, and the step never doubles back. Off by default; `dress`
  /// settles with it when a garment is sewn from a pattern. Springs the length limit cannot bring
  /// back (too few strain_limit_iterations) then no longer shrink the step: a heavy cloth hanging
  /// from two corners reaches 10.9 % with 100 sweeps, against 10.3 % judged by them.
  bool rise_skips_held_springs = false;
  /// Adaptive stepping near colliders: a particle within one spring length of a collider moves at
  /// most this fraction of its springs' mean rest length per step (0: no such bound) [unitless].
  double contact_travel = 1.0;
};

/// Pinned particles driven along a path: turned about `axis` through `centre` at a constant rate and
/// moved at a constant velocity, from time 0 to `until` (then they stay).
struct PinMotion {
  std::vector<int> particles;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< [m]
  double turns_per_second = 0.0;                     ///< [1/s], right-handed about axis
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< [m/s]
  double until = 1e30;                               ///< [s]
};

/// The largest stretch of the model's structural springs at positions x as a step's blow-up check
/// judges it (SimulationOptions::blow_up_strain): the elongation over the rest length, or over a
/// quarter of the mean spring length for a shorter spring [unitless].
double blow_up_stretch(const ClothModel& model, const Eigen::MatrixX3d& x);

/// Throws InputError naming the field when an option is out of range (dt ≤ 0, negative damping, ...).
void check_options(const SimulationOptions& options);

struct StepResult {
  bool ok = true;            ///< false: the step was undone and the state is the last good one
  std::string failure;       ///< why not ok ("non-finite state", "strain 3.2 beyond 1", ...)
  int solver_iterations = 0; ///< CG iterations (0 for direct and explicit)
  int newton_iterations = 0; ///< Newton integrator: iterations taken
  int strain_limit_sweeps = 0;
  int springs_limited = 0;   ///< springs shortened by strain limiting in this step
  int collisions = 0;        ///< particles pushed out of colliders in this step
  int tunnelling = 0;        ///< of those, particles whose path crossed a collider but ended outside it
  int layer_pushes = 0;      ///< particles moved out by the layer-order guard in this step
  int deep_pushes = 0;       ///< particles deeper than one push inside a collider (cloth started inside)
  SelfCollisionResult self;  ///< cloth–cloth collisions of this step
  int stitches_sewn = 0;     ///< stitches newly sewn (within the seam tolerance) in this step
  double dt = 0.0;           ///< the step taken [s] (adaptive stepping may shrink it)
  /// Largest structural strain right after the integrator over the springs the adaptive step
  /// judges (clear of contacts, and of the length limit with rise_skips_held_springs) [unitless].
  double integrator_strain = 0.0;
  double strain = 0.0;             ///< largest structural strain at the end of the step [unitless]
  int retries = 0;           ///< halvings before the step succeeded (adaptive stepping)
  /// Projective dynamics: the largest force left unbalanced on a free particle at the start of the
  /// solve's last iteration, over the heaviest particle's weight (−1: not measured, as with the
  /// double-precision solve), and whether the solve used all its iterations.
  double unbalanced_end = -1.0;
  bool iterations_ran_out = false;
  /// CPU time (this thread's) of the step's phases [s] (of the last try when adaptive stepping retried): the
  /// integrator (forces and solve; of which forces and the system's assembly: force_seconds, implicit
  /// Euler only), the layer guard and length limits, sewing, the collider pass and cloth–cloth collisions.
  double integrate_seconds = 0.0, force_seconds = 0.0, constraint_seconds = 0.0, seam_seconds = 0.0,
         collision_seconds = 0.0, self_collision_seconds = 0.0;
};

struct SettleOptions {
  double max_time = 10.0;        ///< [s] simulated time at most
  double energy_tolerance = 1e-6;  ///< |ΔE_elastic| per step relative to E_elastic (plus 1e-12 J)
  double force_tolerance = 1e-3;   ///< largest static residual force relative to the largest weight
  double record_every = 0.0;     ///< [s] between energy_history samples; 0 = every step
};

struct SettleResult {
  int steps = 0;
  double time = 0.0;                  ///< [s] simulated
  std::string stopped_reason;         ///< "converged", "max_time", or the failure of a step
  bool converged = false;
  double final_residual = 0.0;        ///< largest static residual force / largest weight
  std::vector<double> energy_history; ///< elastic energy samples [J]
};

class TimeIntegrator;

class ClothSimulator {
 public:
  ClothSimulator(ClothModel model, SimulationOptions options);
  ~ClothSimulator();
  ClothSimulator(ClothSimulator&&) noexcept;
  ClothSimulator& operator=(ClothSimulator&&) noexcept;

  /// Pinned vertices keep their positions exactly and have zero velocity. Particles without mass
  /// (vertices in no face: nothing of the cloth) are always pinned, so that they stay where they
  /// are and every integrator's system stays regular.
  void set_pinned(const std::vector<int>& vertices);
  const std::vector<bool>& pinned() const { return pinned_; }
  /// Drives pinned particles (they are pinned by this call); positions at time 0 are the current ones.
  void set_pin_motion(const PinMotion& motion);
  /// Stitches sewn so far (held together by the constraint phase), per ClothModel::seams entry.
  const std::vector<char>& sewn() const { return sewn_; }
  /// Edge–triangle crossings of the cloth at its current positions (seam neighbours excluded).
  int intersections() const;
  /// Projective dynamics with projective.collisions: each particle's normal contact force at the
  /// end of the last step [N] (empty before the first step or without colliders).
  const std::vector<double>& contact_forces() const { return contact_forces_.force; }

  StepResult step();
  /// Steps until the elastic energy and the static residual force settle (a static drape), the
  /// time runs out or a step fails (then the last good state is kept).
  SettleResult settle(const SettleOptions& options);
  /// Largest static residual force (elastic + gravity, on free particles) over the largest weight.
  double static_residual() const;
  double time() const { return time_; }
  /// The step the next step() will try [s]: options().dt unless adaptive stepping shrank it.
  double current_dt() const { return dt_next_ > 0.0 ? dt_next_ : options_.dt; }

  const ClothModel& model() const { return model_; }
  const SimulationOptions& options() const { return options_; }
  const Eigen::MatrixX3d& positions() const { return x_; }
  const Eigen::MatrixX3d& velocities() const { return v_; }
  void set_state(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& v);

  double elastic_energy() const;
  double kinetic_energy() const;
  double gravity_energy() const;  ///< −Σ m g·x [J]
  /// Total force on each particle [N] (springs, damping, air, gravity); zero rows for pinned ones.
  Eigen::MatrixX3d forces() const;
  /// The same into f, reusing its storage (no allocation when it already has #V rows).
  void forces(Eigen::MatrixX3d& f) const;
  /// Largest and mean strain over structural springs.
  double max_strain() const;
  double mean_strain() const;

  /// −∂f/∂x of the elastic forces, 3#V × 3#V, lower and upper parts; with clamp_geometric the
  /// compressed springs' transverse terms are dropped (positive semi-definite result).
  Eigen::SparseMatrix<double> stiffness_matrix(bool clamp_geometric) const;

 private:
  // The integrators and the implicit system read and advance the state (cloth/src/integrator.h).
  friend class SymplecticEuler;
  friend class ImplicitEuler;
  friend class Newton;
  friend class ProjectiveDynamics;
  friend class SystemMatrix;
  std::unique_ptr<TimeIntegrator> integrator_;
  void add_spring_forces(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& v, Eigen::MatrixX3d& f) const;
  /// all: look at every spring; false: only those with an end moved since the last call ended with
  /// every spring within its bounds. after_contact: a particle that a collider pass of this step
  /// pushed out slides along the collider's surface instead of being pulled back into it.
  void limit_strain(const Eigen::MatrixX3d& x_before, StepResult& r, bool all, bool after_contact = false);
  Eigen::MatrixX3d contact_normal_;  ///< per particle: the normal of its last push in this step, or 0
  std::vector<char> limit_active_, limit_next_;  ///< limit_strain's active sets (work arrays)
  std::vector<char> limit_held_;  ///< limit_strain: moved by a contact pass since its last call
  /// limit_strain: each particle's length-limited springs, ascending (CSR: the springs of particle
  /// p are limit_springs_[limit_first_[p] .. limit_first_[p + 1])), and a per-spring mark.
  std::vector<int> limit_first_, limit_springs_, limit_mark_;
  int limit_stamp_ = 0;  ///< limit_strain: the mark of the current sweep's queued springs
  Eigen::MatrixX3d limit_end_;   ///< the positions at the end of the last limit_strain
  bool limit_converged_ = false;  ///< ... and whether every spring was then within its bounds
  void collide(const Eigen::MatrixX3d& x_start, StepResult& r);
  /// Returns the particle's distance from the collider where it ends [m].
  double push_out(const Collider& c, double margin, int i);
  void keep_layer_order(StepResult& r);
  /// Sews the stitches that have come within the tolerance and holds the sewn ones closed; returns
  /// the widest gap of a sewn stitch before it was closed [m].
  double sew(StepResult& r, bool draw);
  void draw_stitch(int k, double reach);
  Eigen::Vector3d meeting_point(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
  void move_pins(double t);
  /// Finds the particles in the colliders' penalty zones at the current positions (contacts_).
  void find_contacts();
  /// A lower bound of particle i's distance from collider c at p, from its last lookup in collide()
  /// (the distance changes by at most 1.75 × the travel); −∞ before the first [m].
  double distance_lower_bound(int i, int c, const Eigen::Vector3d& p) const;
  /// start_distance_ from the current positions (every particle, every collider).
  void find_inside();
  /// The distance from the colliders a particle must reach this step: `margin`, or for a particle
  /// that started the step within a collider's margin (inside it, or placed there) its distance
  /// then plus what it may exit by in a step (deep_push_speed_ × dt) [m].
  double exit_margin(int i, double margin) const;
  /// Per particle: its distance to the nearest collider at the start of the step when that is
  /// within the margin (after the last collider pass, which leaves only particles that started
  /// inside there), else +∞ [m]; end_distance_: the same at the end of the last collider pass.
  Eigen::VectorXd start_distance_, end_distance_;
  void add_penalty_forces(Eigen::MatrixX3d& f) const;
  StepResult try_step(double dt);
  /// What a step changes and an undone step must put back.
  struct Snapshot;
  Snapshot snapshot() const;
  void restore(const Snapshot& s);
  /// Largest structural strain over the springs with neither end within a collider's margin at the
  /// start of the step (the adaptive step's measure: contacts move particles by distances that a
  /// smaller step does not shrink), nor marked in held_at_limit_.
  double free_strain() const;
  /// Marks the springs held at the length limit at the current positions (rise_skips_held_springs).
  void mark_held_springs();
  /// Adaptive stepping: the largest step that the contacts and (symplectic Euler) the stiffest
  /// spring allow at the current state [s] (infinity when nothing bounds it).
  double step_bound();
  /// Why a step failed the blow-up check: the most strained structural spring, its particles and
  /// strain, the time, and whether the integrator or the passes after it (positions x_integrated
  /// in between) stretched it.
  std::string blow_up_report(const Eigen::MatrixX3d& x_integrated, double t) const;
  /// The largest structural spring stretch as blow_up_strain judges it: elongation over the rest
  /// length, or over blow_up_length_ for a shorter spring (a sub-millimetre spring of a garment's
  /// detail moved a millimetre by a contact has not diverged; a step that diverges stretches
  /// springs by lengths, not by ratios of tiny ones).
  double blow_up_stretch(const Eigen::MatrixX3d& x) const;
  Eigen::Vector3d wind_at(double t) const;
  double allowed_length(int s) const;

  ClothModel model_;
  SimulationOptions options_;
  Eigen::MatrixX3d x_, v_;
  std::vector<bool> pinned_;
  Eigen::VectorXd inverse_mass_;  ///< 0 for pinned particles
  std::vector<char> sewn_;        ///< per stitch
  std::vector<int> joined_;       ///< seam representatives (cloth/seams.h)
  std::shared_ptr<SelfCollision> self_;  ///< cloth–cloth collisions, when switched on and there are faces
  PinMotion pin_motion_;
  Eigen::MatrixX3d pin_start_;    ///< driven pins' positions at time 0 (rows of pin_motion_.particles)
  double time_ = 0.0;
  double dt_ = 0.0;
  double dt_next_ = 0.0;  ///< adaptive stepping: the controller's next step [s] (0: not started)
  int calm_steps_ = 0;
  std::vector<char> held_at_limit_;  ///< per spring: left out of free_strain (empty: none)
  Eigen::VectorXd contact_length_;  ///< per particle: mean structural rest length [m] (step_bound)
  std::vector<double> inv_rest_;                     ///< 1 / rest length per spring (force loop)
  double layer_push_cap_ = 0.0;                      ///< largest layer-guard push per step [m]
  double blow_up_length_ = 0.0;  ///< a quarter of the mean spring length: blow_up_stretch's floor [m]
  double deep_push_speed_ = 0.0;  ///< largest speed out of a collider for a particle that started inside [m/s]
  /// Particles in a penalty zone at the current positions, found by the collision pass that ends
  /// every step (so the next step's forces need no distance query): particle, collider, outward
  /// normal and depth into the zone [m].
  struct Contacts {
    std::vector<int> particle, collider;
    std::vector<Eigen::Vector3d> normal;
    std::vector<double> depth;
    void clear() { particle.clear(), collider.clear(), normal.clear(), depth.clear(); }
    void add(int p, int c, const Eigen::Vector3d& n, double d) {
      particle.push_back(p), collider.push_back(c), normal.push_back(n), depth.push_back(d);
    }
  } contacts_;
  /// Per collider: each particle's position and distance at its last lookup in collide().
  std::vector<Eigen::MatrixX3d> lookup_x_;
  Eigen::MatrixXd lookup_d_;
  /// Per particle and collider (particle-major): the body grid cell of its last lookup, so that a
  /// particle looked up again in the same cell reads its corners from here (MeshDistance::Cell).
  mutable std::vector<MeshDistance::Cell> lookup_cell_;
  MeshDistance::Cell* lookup_cell(int i, int c) const {
    const std::size_t colliders = options_.colliders.size(), want = static_cast<std::size_t>(x_.rows()) * colliders;
    if (lookup_cell_.size() != want) lookup_cell_.assign(want, MeshDistance::Cell{});
    return &lookup_cell_[static_cast<std::size_t>(i) * colliders + static_cast<std::size_t>(c)];
  }
  /// Projective dynamics' contacts (projective.collisions): per particle the normal contact force
  /// [N] (0: none), its collider (−1: none) and its normal at the last pass, kept between steps.
  struct ContactForces {
    std::vector<double> force;
    std::vector<int> collider;
    std::vector<Eigen::Vector3d> normal;
  } contact_forces_;
  struct Snapshot {
    Eigen::MatrixX3d x, v;
    ContactForces contact_forces;
    Contacts contacts;
    std::vector<char> sewn;
  };
};

}  // namespace dresskit::cloth
