// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/controls.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/archive.hpp"
#include "core/error.hpp"

namespace dda {

namespace {

constexpr double kInf = 1e308;
constexpr ControlRange kPositive{0, kInf, true, false, "must be positive"};
constexpr ControlRange kZeroOrPositive{0, kInf, false, false, "must be zero or positive"};
constexpr ControlRange kUnitInterval{0, 1, false, false, "must lie in [0, 1]"};
constexpr ControlRange kOpenUnitInterval{0, 1, true, true, "must lie in (0, 1)"};
constexpr ControlRange kFraction{0, 1, false, true, "must lie in [0, 1)"};
constexpr ControlRange kAtLeastOne{1, kInf, false, false, "must be at least 1"};
constexpr ControlRange kZeroOffOrPositive{0, kInf, false, false, "must be zero (off) or positive"};
constexpr ControlRange kZeroAutomaticOrPositive{0, kInf, false, false, "must be zero (automatic) or positive"};
constexpr ControlRange kOffOrUnitInterval{-1, 1, false, false, "must be -1 (off) or lie in [0, 1]", true};
constexpr ControlRange kThreads{0, kMaxThreads, false, false, "must be zero (every core) or 1 to 4096"};
constexpr ControlRange kAutomaticZeroOrPositive{
    -1, kInf, false, false, "must be -1 (from the loads), 0 (first-order blocks) or positive", true};

constexpr const char* kPlaneNames[] = {"stress", "strain"};                                  // PlaneMode order
constexpr const char* kIntegratorNames[] = {"shi", "newmark", "generalized_alpha", "auto"};  // Integrator order
constexpr const char* kMeshMassNames[] = {"consistent", "lumped", "mixed", "auto"};          // MeshMass order
constexpr const char* kContactLawNames[] = {"holding", "shi"};                               // ContactLaw order
constexpr const char* kPreconditionerNames[] = {"auto", "block_jacobi", "multigrid"};        // Preconditioning order
constexpr const char* kSolverNames[] = {"auto", "pcg", "cholmod"};                           // SolverKind order
constexpr const char* kFillOrderingNames[] = {"metis", "amd"};                               // FillOrdering order
constexpr const char* kMeshPreconditionerNames[] = {"block_factor", "node_jacobi"};  // MeshPreconditioning order

constexpr ControlSpec number(const char* name, double& (*field)(Controls&), ControlRange range, const char* doc,
                             const char* default_text = nullptr) {
  return {name, ControlType::Number, doc, default_text, range, {}, field, nullptr, nullptr, nullptr, nullptr, nullptr};
}
constexpr ControlSpec integer(const char* name, int& (*field)(Controls&), ControlRange range, const char* doc) {
  return {name, ControlType::Integer, doc, nullptr, range, {}, nullptr, field, nullptr, nullptr, nullptr, nullptr};
}
constexpr ControlSpec flag(const char* name, bool& (*field)(Controls&), const char* doc) {
  return {name, ControlType::Flag, doc, nullptr, {}, {}, nullptr, nullptr, field, nullptr, nullptr, nullptr};
}
constexpr ControlSpec vector(const char* name, Vec2& (*field)(Controls&), const char* doc) {
  return {name, ControlType::Vector, doc, nullptr, {}, {}, nullptr, nullptr, nullptr, field, nullptr, nullptr};
}
constexpr ControlSpec choice(const char* name, std::span<const char* const> names, int (*get)(const Controls&),
                             void (*set)(Controls&, int), const char* doc) {
  return {name, ControlType::Choice, doc, nullptr, {}, names, nullptr, nullptr, nullptr, nullptr, get, set};
}

// One row per control, in the order Lua lists them. The doc strings are the
// "meaning" column of docs/lua_api.md's controls table.
const ControlSpec kControls[] = {
    choice(
        "plane", kPlaneNames, [](const Controls& c) { return static_cast<int>(c.plane); },
        [](Controls& c, int i) { c.plane = static_cast<PlaneMode>(i); },
        "`\"stress\"` or `\"strain\"` (plane stress / plane strain elasticity)"),
    number(
        "g0", [](Controls& c) -> double& { return c.g0; }, kZeroOrPositive,
        "normal contact spring stiffness (N/m); 0 = 50 × the largest E"),
    number(
        "g1", [](Controls& c) -> double& { return c.g1; }, kZeroOrPositive,
        "upper limit of the time step (s); 0 = the default rule (docs/time_step.md, \"The default time "
        "step\"): a model moved by gravity alone takes sqrt(h_min/|g|)/20, a dynamically loaded one that moves as "
        "bodies (blocks and model within the loads' wavelengths) 1/(20 f) and that, any other the paper's Eqs. 1–3; "
        "the run log says which"),
    number(
        "g2", [](Controls& c) -> double& { return c.g2; }, kPositive,
        "largest step displacement / half the model height; exceeding it cuts Δt"),
    number(
        "gg", [](Controls& c) -> double& { return c.gg; }, kUnitInterval,
        "dynamic parameter in [0, 1]: share of the velocity carried to the next step (1 = fully dynamic, "
        "0 = static)"),
    choice(
        "integrator", kIntegratorNames, [](const Controls& c) { return static_cast<int>(c.integrator); },
        [](Controls& c, int i) { c.integrator = static_cast<Integrator>(i); },
        "time integration (`docs/time_integration.md`): `\"auto\"`, Shi's scheme, or, where the dynamic loads "
        "had the blocks meshed (`docs/waves.md`), Newmark's average acceleration; `\"shi\"`, the paper's scheme "
        "(Newmark β = ½, γ = 1: "
        "first order, it damps a wave of angular frequency ω by about exp(−ω²Δt·t/4)); `\"newmark\"`, "
        "average acceleration (β = ¼, γ = ½: second order, no numerical damping); "
        "`\"generalized_alpha\"` (Chung–Hulbert: second order, damping only near the step's own "
        "frequency, as `rho_inf` says)"),
    number(
        "rho_inf", [](Controls& c) -> double& { return c.rho_inf; }, kUnitInterval,
        "`generalized_alpha` only: spectral radius at infinite frequency, in [0, 1]; 1 = no numerical "
        "damping, 0 = the most (asymptotic annihilation)"),
    number(
        "shear_ratio", [](Controls& c) -> double& { return c.shear_ratio; }, kZeroOrPositive,
        "shear contact spring = shear_ratio × g0 (Shi's 2/5)"),
    integer(
        "open_close_limit", [](Controls& c) -> int& { return c.open_close_limit; }, kAtLeastOne,
        "open-close iterations before Δt is cut and the step redone"),
    number(
        "contact_tolerance", [](Controls& c) -> double& { return c.contact_tolerance; }, kZeroOrPositive,
        "open-close hysteresis under `contact_law = \"shi\"`, fraction of half the model height, of every "
        "decision; `\"holding\"` does not use it: its bands are shares of the spread of the step's block "
        "translations, 1e-2 for friction and 1e-4 for gaps and intact joints (docs/contacts.md)"),
    choice(
        "contact_law", kContactLawNames, [](const Controls& c) { return static_cast<int>(c.contact_law); },
        [](Controls& c, int i) { c.contact_law = static_cast<ContactLaw>(i); },
        "`\"holding\"` (default): a contact's shear force is continuous through its changes of state (a "
        "contact that locks again keeps the force its spring carried), friction agrees with the normal force "
        "of the accepted solve, its open-close and friction decisions have bands in the step's units (no "
        "length of the model, no force through g0), and joints without cohesion or tension are unbonded "
        "from the start: a block that must hold on a slope holds, and one that slides does so at the "
        "closed-form rate, from Δt = 1e-2 to 1e-4 s; at smaller Δt a block's strain modes can chatter on its "
        "contacts (at 1e-5 s a sliding block; a 0.5 m block that must hold, loaded at once, creeps; under "
        "`\"shi\"` too; `strain_damping` or `friction_lag` cures it). `\"shi\"`: Shi's law (1988), "
        "the paper's: a contact that closes or locks again does so unloaded, "
        "and a block that must stay on a slope creeps down it at small Δt; the paper's scripts pin it to "
        "reproduce the paper's figures and the validation report (docs/contacts.md)"),
    number(
        "strain_damping", [](Controls& c) -> double& { return c.strain_damping; }, kZeroOffOrPositive,
        "s: Kelvin–Voigt damping of the blocks' strains, σ = E(ε + β·ε̇) with β this value: a damping ratio "
        "βω/2 at angular frequency ω, a material damping of the rock. Friction couples a sliding block's "
        "strain modes into a vibration that grows where Shi's scheme no longer damps it (Δt ≤ 1e-5 s; under "
        "`\"newmark\"` at every Δt): the block chatters. 5e-5 (12 % at the 750 Hz of a 1 m granite block) "
        "keeps such a block sliding at the closed-form rate on φ up to 25°; a larger φ or a larger block "
        "(lower ω) needs more. A wave of those frequencies is damped as much: the paper's bar loses 5 % of its "
        "peak at 1e-6 (`docs/friction_flutter.md`)",
        "0 (off)"),
    number(
        "friction_lag", [](Controls& c) -> double& { return c.friction_lag; }, kZeroOffOrPositive,
        "s: friction that lags the normal force by t_r, this value: the normal force N_f a contact's friction "
        "strength acts with follows N as dN_f/dt = (N − N_f)/t_r (the simplified Prakash–Clifton law), stepped "
        "exactly for any Δt (Δt ≫ t_r: no lag); in steady sliding N_f = N, and a contact that closes (a landing) "
        "is a new interface: its N_f is the mean of the N it has carried since. The fast swings of N that couple a "
        "sliding block's strain modes into chatter (Δt ≤ 1e-5 s) "
        "do not reach its friction: with 3e-3, under `contact_law = \"holding\"` and Shi's integrator, a 1 m "
        "granite block slides at the closed-form rate with its contacts closed at Δt = 1e-2 to 1e-6 s, φ up to "
        "45° (with gravity switched on at once, up to 25° below 1e-5 s), and waves through intact joints are "
        "untouched. Not the default: under `\"shi\"` it lets that law's model-wide band hold a block that "
        "must slide (`docs/friction_flutter.md`)",
        "0 (off)"),
    number(
        "restitution", [](Controls& c) -> double& { return c.restitution; }, kOffOrUnitInterval,
        "the landing law: a contact that lands (open at the step's start and approaching faster than 2·g·max(Δt, "
        "its slowest ring), closed by the step, its blocks held by no other closed contact) ends the step as a "
        "rigid-body impact with this coefficient of "
        "restitution e in [0, 1] would end it: it leaves at e times its approach speed (at 0 it stays on the "
        "face), its contact point stops if Coulomb's bound μ·(normal impulse) allows, else slides with that "
        "impulse, the same at every Δt. -1: off, the penalty springs' bounce (about 0.76 at Δt = 1e-3 s, another "
        "at each Δt). Integrator `\"shi\"` and first-order blocks only (`docs/landings.md`)",
        "-1 (off)"),
    number(
        "contact_range", [](Controls& c) -> double& { return c.contact_range; }, kZeroOrPositive,
        "m: blocks closer than this at the start of a step are in contact; a step in which a vertex moves"
        " more than range / 2.5 is cut and redone. Automatic: starts at a tenth of the median edge length"
        " and widens (the step redone with the same Δt) whenever a vertex moves further than range / 2.5,"
        " up to Shi's 2.5·g2·(half height)",
        "0 (automatic)"),
    number(
        "mesh_size", [](Controls& c) -> double& { return c.mesh_size; }, kAutomaticZeroOrPositive,
        "m: blocks added from now on whose rock material has no `mesh_size` of its own are meshed into "
        "constant-strain triangles of about this size, with continuous displacement inside and contacts"
        " on the outline (`docs/meshed_blocks.md`); convex blocks on a structured grid, concave ones by CGAL. 0: "
        "first-order blocks. -1: from the dynamic loads: before the first step, where a block is larger than the "
        "element that resolves the loads' shortest shear wave (12 elements per wavelength at the frequency "
        "below which 99 % of their energy lies), every block is meshed at that size (`docs/waves.md`)",
        "-1 (from the loads)"),
    choice(
        "mesh_mass", kMeshMassNames, [](const Controls& c) { return static_cast<int>(c.mesh_mass); },
        [](Controls& c, int i) { c.mesh_mass = static_cast<MeshMass>(i); },
        "the mass of meshed blocks' elements (`docs/meshed_blocks.md`): `\"auto\"`, lumped under dynamic loads "
        "(`docs/waves.md`), consistent otherwise; `\"consistent\"` (ρ∫TᵀT, exact: "
        "short waves run faster than c, a precursor ahead of a steep front), `\"lumped\"` (a third of an "
        "element's mass at each corner: short waves lag) or `\"mixed\"` (their mean). Translation and the "
        "mass are exact under each; first-order blocks keep their consistent mass"),
    number(
        "max_frequency", [](Controls& c) -> double& { return c.max_frequency; }, kZeroAutomaticOrPositive,
        "Hz: the highest frequency of the dynamic loads, as the user states it; 0: found from the loads' "
        "histories and functions (the frequency below which 99 % of each one's energy lies; `docs/waves.md`). "
        "The element size of `mesh_size = -1` follows from it",
        "0 (from the loads)"),
    number(
        "fixed_point_factor", [](Controls& c) -> double& { return c.fixed_point_factor; }, kPositive,
        "fixed-point spring = factor × g0"),
    vector(
        "gravity", [](Controls& c) -> Vec2& { return c.gravity; }, "gravity vector (m/s²), e.g. `{0, -9.81}`"),
    number(
        "cut_factor", [](Controls& c) -> double& { return c.cut_factor; }, kOpenUnitInterval,
        "Δt multiplier when a step is redone, in (0, 1)", "1/3"),
    integer(
        "max_step_cuts", [](Controls& c) -> int& { return c.max_step_cuts; }, kZeroOrPositive,
        "cuts in one step before the step fails with an error"),
    number(
        "cg_tolerance", [](Controls& c) -> double& { return c.cg_tolerance; }, kPositive,
        "relative residual of the conjugate-gradient solve (of the accepted solution)"),
    number(
        "cg_open_close_tolerance", [](Controls& c) -> double& { return c.cg_open_close_tolerance; }, kPositive,
        "relative residual while contact states still change, used after a step whose solves took over 30"
        " CG iterations (walls). Wave problems solve every open-close iteration tightly: their residual "
        "is measured against a right-hand side that the blocks' inertia dominates, and 1e-4 of it moved "
        "the reflected amplitudes of Fig. 11 (Models 5 and 6) by 8–13 % from where the scheme converges; "
        "once the states hold, the solve is tightened to `cg_tolerance` and the states checked again. "
        "Equal to `cg_tolerance`: solve tightly every time. That is the plain scheme, whose last solve's "
        "friction lags a solve with other contact states. On walls its answer differs from the default "
        "scheme's by up to 6 % (`docs/performance.md`)"),
    number(
        "cg_static_tolerance", [](Controls& c) -> double& { return c.cg_static_tolerance; }, kPositive,
        "relative residual of the accepted solution in static analysis (`gg = 0`) after a step whose "
        "solves took over 30 CG iterations (walls); the larger of it and `cg_tolerance` applies. There "
        "the friction already carries the error of the loose open-close solves and no velocity carries a "
        "displacement error on, so tighter solves change the answer less than the loose solves do "
        "(wall(20), 300 steps: 1e-6 and 1e-10 agree to 1.7e-11 m, and both end 7.5e-8 m from the scheme's"
        " limit with every solve at 1e-12 or tighter); wall(40) runs 1.6× faster than at 1e-10. Dynamic "
        "analysis keeps `cg_tolerance` (a wall with `gg = 1` moved 15× further from the converged answer "
        "at 1e-6). Equal to `cg_tolerance`: off"),
    flag(
        "predict_states", [](Controls& c) -> bool& { return c.predict_states; },
        "in wave problems (steps after short solves, where the warm start extrapolates the motion), start"
        " each step's open-close iteration from the contact states the warm start implies: contacts that "
        "close, and closed contacts that start or stop sliding; never an opening or a joint failure, "
        "which only a solve decides. Fewer open-close iterations in wave problems (blast(2) over its 0.05"
        " s: 2.95 → 2.08 per step); the answer is another consistent set of states, so results differ "
        "from `false` beyond round-off (blast(2) PPV at MP1 by 0.2 %)"),
    integer(
        "patch_hops", [](Controls& c) -> int& { return c.solver.pcg.patch_hops; }, kZeroOffOrPositive,
        "in wave problems, a re-solve after contacts changed state first solves on the rows of those "
        "contacts' blocks and the rows within this many couplings of them, the rest held; then the whole "
        "residual is checked and the solve finished over all rows if need be, so it meets `cg_tolerance` "
        "either way. Where the blocks' inertia dominates their springs (the paper's blast) a local change"
        " stays local: blast(0.5) takes 7.0 instead of 12.5 iterations over all rows per step (plus 5.5 "
        "on patches of a few hundred rows). Not used where the patch would exceed a quarter of the rows, "
        "nor after long solves (walls); 0: off. The answer differs from `0` within the CG tolerance (and "
        "what the open-close iteration's hysteresis makes of that)"),
    number(
        "jacobi_refresh_tolerance", [](Controls& c) -> double& { return c.solver.pcg.jacobi_refresh_tolerance; },
        kFraction,
        "block-Jacobi keeps a block's inverse while every entry of the diagonal block stays within this "
        "fraction (of its largest entry) of the block it was made from; in [0, 1), 0: invert every "
        "rewritten block. Changes how fast the solve converges; the answer only as far as the loose "
        "open-close solves' stopping points reach it (through the normal force friction uses), or beyond "
        "`cg_tolerance` not at all with `cg_open_close_tolerance = cg_tolerance`"),
    choice(
        "solver", kSolverNames, [](const Controls& c) { return static_cast<int>(c.solver.kind); },
        [](Controls& c, int i) { c.solver.kind = static_cast<SolverKind>(i); },
        "`\"auto\"`, `\"pcg\"` or `\"cholmod\"`: the linear solver. `\"pcg\"`: conjugate gradients with "
        "block-Jacobi or multigrid (`preconditioner`), cheap where the blocks' inertia dominates (waves). "
        "`\"cholmod\"`: CG preconditioned with a sparse Cholesky factor (CHOLMOD) kept across open-close "
        "iterations and steps and refreshed after `refactor_iterations`, for stiff systems (walls, slopes). "
        "`\"auto\"`: PCG, and the factor after two steps whose solves took over 30 CG iterations each, kept "
        "while its counted work per step stays below PCG's; `m:stats().solver` says which ran. Results "
        "differ between the solvers within the solve tolerance (and what the open-close iteration makes of "
        "that)"),
    integer(
        "refactor_iterations", [](Controls& c) -> int& { return c.solver.cholmod.refactor_iterations; }, kAtLeastOne,
        "with `solver = \"cholmod\"`: CG iterations a solve may take with the factor of an earlier system "
        "before the current system is factorised (then the solve goes on from where it got)"),
    choice(
        "fill_ordering", kFillOrderingNames,
        [](const Controls& c) { return static_cast<int>(c.solver.cholmod.ordering); },
        [](Controls& c, int i) { c.solver.cholmod.ordering = static_cast<FillOrdering>(i); },
        "`\"metis\"` (nested dissection) or `\"amd\"`: the fill-reducing ordering of the CHOLMOD factor, "
        "computed on the block graph"),
    choice(
        "preconditioner", kPreconditionerNames,
        [](const Controls& c) { return static_cast<int>(c.solver.pcg.preconditioner); },
        [](Controls& c, int i) { c.solver.pcg.preconditioner = static_cast<Preconditioning>(i); },
        "`\"auto\"`, `\"block_jacobi\"` or `\"multigrid\"`"),
    choice(
        "mesh_preconditioner", kMeshPreconditionerNames,
        [](const Controls& c) { return static_cast<int>(c.solver.mesh_preconditioner); },
        [](Controls& c, int i) { c.solver.mesh_preconditioner = static_cast<MeshPreconditioning>(i); },
        "models with meshed blocks: `\"block_factor\"` (each meshed block's nodal matrix, a Cholesky "
        "factor kept across solves while they take few CG iterations) or `\"node_jacobi\"` (the nodes' 2×2 "
        "diagonal blocks); first-order blocks keep block-Jacobi (`docs/meshed_blocks.md`)"),
    integer(
        "cg_max_iterations", [](Controls& c) -> int& { return c.cg_max_iterations; }, kZeroAutomaticOrPositive,
        "0 = automatic"),
    integer(
        "threads", [](Controls& c) -> int& { return c.threads; }, kThreads,
        "worker threads (0 = every core); `--threads` overrides it"),
};

// Read access through the setters' accessors (they only return a reference).
Controls& writable(const Controls& c) { return const_cast<Controls&>(c); }

// A default as the docs write it: %g, and below 1e-3 the shortest exponent
// form that reads back the same, without padding (1e-9, not 1e-09).
std::string number_text(double v) {
  if (std::isnan(v)) return "nan";  // (printf writes "-nan" for most NaNs)
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", v);
  if (v != 0 && std::abs(v) < 1e-3)
    for (int digits = 0; digits < 17; ++digits) {
      std::snprintf(buf, sizeof buf, "%.*e", digits, v);
      if (std::strtod(buf, nullptr) == v) break;
    }
  std::string s;
  for (const char* p = buf; *p; ++p)
    if (!(p[0] == '0' && p > buf + 1 && p[-1] == '-' && p[-2] == 'e')) s += *p;  // 1e-09 → 1e-9
  return s;
}

}  // namespace

std::span<const ControlSpec> control_specs() { return kControls; }

const ControlSpec* find_control(std::string_view name) {
  for (const ControlSpec& s : kControls)
    if (name == s.name) return &s;
  return nullptr;
}

const char* ControlSpec::violated(const Controls& c) const {
  switch (type) {
    case ControlType::Number: {
      const double v = number(writable(c));
      return std::isfinite(v) && range.admits(v) ? nullptr : range.rule;
    }
    case ControlType::Integer:
      return range.admits(integer(writable(c))) ? nullptr : range.rule;
    case ControlType::Flag:
      return nullptr;
    case ControlType::Vector:
      return vector(writable(c)).allFinite() ? nullptr : "must be finite";
    case ControlType::Choice: {
      const int i = get_choice(c);
      return i >= 0 && i < static_cast<int>(choices.size()) ? nullptr : "is not one of its choices";
    }
  }
  return nullptr;
}

std::string ControlSpec::value_text(const Controls& c) const {
  switch (type) {
    case ControlType::Number:
      return msg(number(writable(c)));
    case ControlType::Integer:
      return msg(integer(writable(c)));
    case ControlType::Flag:
      return flag(writable(c)) ? "true" : "false";
    case ControlType::Vector: {
      const Vec2 v = vector(writable(c));
      return msg("{", v.x(), ", ", v.y(), "}");
    }
    case ControlType::Choice: {
      const int i = get_choice(c);
      return i >= 0 && i < static_cast<int>(choices.size()) ? msg("\"", choices[i], "\"") : msg(i);
    }
  }
  return "";
}

int ControlSpec::find_choice(std::string_view name) const {
  for (std::size_t i = 0; i < choices.size(); ++i)
    if (name == choices[i]) return static_cast<int>(i);
  return -1;
}

std::string ControlSpec::choice_list() const {
  std::string s;
  for (std::size_t i = 0; i < choices.size(); ++i)
    s += msg(i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ", "\"", choices[i], "\"");
  return s;
}

void validate_controls(const Controls& c) {
  // Runs every step: a message is built only when a check fails.
  for (const ControlSpec& s : kControls)
    if (const char* rule = s.violated(c)) throw Error(msg("controls: ", s.name, " ", rule, ", got ", s.value_text(c)));
}

namespace {
// One control's value, either way.
template <class Archive>
void archive_value(Archive& ar, const ControlSpec& s, Controls& c) {
  switch (s.type) {
    case ControlType::Number:
      ar(s.number(c));
      break;
    case ControlType::Integer:
      ar(s.integer(c));
      break;
    case ControlType::Flag:
      ar(s.flag(c));
      break;
    case ControlType::Vector:
      ar(s.vector(c));
      break;
    case ControlType::Choice: {
      int choice = s.get_choice(c);
      ar(choice);
      if constexpr (Archive::reading) s.set_choice(c, choice);
      break;
    }
  }
}
}  // namespace

void archive_controls(ArchiveWriter& ar, Controls& c) {
  ar(std::uint64_t(std::size(kControls)));
  for (const ControlSpec& s : kControls) {
    ar(std::string(s.name), s.type);
    archive_value(ar, s, c);
  }
}

// By name: a control the file lacks keeps its default.
void archive_controls(ArchiveReader& ar, Controls& c) {
  std::uint64_t n = 0;
  ar(n);
  for (std::uint64_t k = 0; k < n; ++k) {
    std::string name;
    ControlType type{};
    ar(name, type);
    const ControlSpec* s = find_control(name);
    if (!s || s->type != type)
      throw Error(msg(ar.what(), " holds a control '", name.substr(0, 40),
                      "' this dda does not know (damaged, or written by another build of dda)"));
    archive_value(ar, *s, c);
    if (const char* rule = s->violated(c))
      throw Error(msg(ar.what(), " is damaged: its control ", s->name, " ", rule, ", got ", s->value_text(c)));
  }
}

std::string controls_markdown_table() {
  const Controls defaults;
  std::string out = "| option | default | meaning |\n|---|---|---|\n";
  for (const ControlSpec& s : kControls) {
    std::string def;
    if (s.default_text)
      def = s.default_text;
    else if (s.type == ControlType::Number)
      def = number_text(s.number(writable(defaults)));
    else if (s.type == ControlType::Integer)
      def = s.value_text(defaults);
    else
      def = msg("`", s.value_text(defaults), "`");
    out += msg("| `", s.name, "` | ", def, " | ", s.doc, " |\n");
  }
  return out;
}

}  // namespace dda
