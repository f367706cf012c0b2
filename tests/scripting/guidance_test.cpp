// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// What the engine chooses for a user who sets nothing: the default time step
// (world/time_step_rule.hpp), settling to equilibrium before a dynamic run
// (m:settle, world/settle.hpp), and the peaks of vector fields (monitor:ppv,
// monitor:peak("velocity")). Each against a closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "lua_state_test.hpp"
#include "script_helpers.hpp"

using namespace dda::script;

namespace {

class Guidance : public dda::test::LuaStateTest {
 protected:
  void SetUp() override {
    out_ = std::make_unique<dda::test::TempDir>(::testing::UnitTest::GetInstance()->current_test_info()->name());
    Session s;
    s.out_dir = out_->path;
    start(std::move(s));
  }
  double number(const char* global) {
    lua_getglobal(L, global);
    const double v = lua_tonumber(L, -1);
    lua_pop(L, 1);
    return v;
  }
  std::unique_ptr<dda::test::TempDir> out_;
};

constexpr double kG = 9.81;

// A model moved by gravity alone takes Δt = sqrt(h_min/|g|)/20 (h_min: the
// block's area over its longest edge); a load makes it dynamic, and Δt is
// the paper's min(0.05·h_min/C_P, 0.354·sqrt(m_min/g0)). Exact formulas:
// tolerance 1e-12 of each.
TEST_F(Guidance, DefaultTimeStepFollowsWhatMovesTheModel) {
  run("m = dda.model{ plane = 'strain', gravity = {0, -9.81} }\n"
      "rock = m:rock{ density = 2500, E = 10e9, nu = 0.25 }\n"
      "b = m:add_block{ {0, 0}, {2, 0}, {2, 0.5}, {0, 0.5} }\n"
      "gravity_dt = m:suggested_dt()\n"
      "m:point_load{ at = {1, 0.25}, fx = 1e3 }\n"
      "loaded_dt = m:suggested_dt()\n"
      "m:controls{ max_frequency = 10 }\n"
      "bodies_dt = m:suggested_dt()\n"
      "m:controls{ max_frequency = 2000 }\n"
      "waves_dt = m:suggested_dt()\n");
  const double h = 1.0 / 2.0;  // area 1 m² over the longest edge, 2 m
  EXPECT_NEAR(number("gravity_dt"), std::sqrt(h / kG) / 20, 1e-12 * std::sqrt(h / kG) / 20);
  const double E = 10e9, nu = 0.25, rho = 2500;
  const double cp = std::sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)));  // plane strain
  const double paper = std::min(0.05 * h / cp, 2 * 0.177 * std::sqrt(rho * 1.0 / (50 * E)));
  EXPECT_NEAR(number("loaded_dt"), paper, 1e-12 * paper);  // a held load: no frequency
  // At 10 Hz the block (2 m) is within the 10.5 m element that resolves the
  // shear wave and the model within a wavelength: it moves as a body, Δt
  // follows the load (1/(20 f) = 5 ms, under Δt_g = 11.3 ms). At 2000 Hz
  // (elements of 0.053 m) the waves inside it count: the paper's rule.
  EXPECT_NEAR(number("bodies_dt"), 1.0 / 200, 1e-12);
  EXPECT_NEAR(number("waves_dt"), paper, 1e-12 * paper);
}

// The run log says which Δt the default rule chose and why.
TEST(GuidanceLog, RunLogNamesTheDefaultTimeStepAndItsRule) {
  dda::test::TempDir dir("dt-log");
  dda::test::write_file(dir / "drop.lua",
                        "local m = dda.model{ gravity = {0, -9.81} }\n"
                        "m:rock{ density = 2000, E = 1e9, nu = 0.2 }\n"
                        "m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\n"
                        "m:step(2)\n");
  const auto r = dda::test::run_dda("run drop.lua --quiet --out out", dir.path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string log = dda::test::read_file(dir / "out" / "run.log");
  EXPECT_NE(log.find("time step: g1 = 0, the default rule"), std::string::npos) << log;
  EXPECT_NE(log.find("moved by gravity alone"), std::string::npos) << log;
  EXPECT_NE(log.find("sqrt(h_min/|g|)/20, h_min = 1 m"), std::string::npos) << log;
}

// A stack of n = 10 blocks of 1 m on a fixed base, settled under gravity:
// each block carries the weight above its mid-height, σyy = −ρ·g·(depth of
// its centroid) (the column's equilibrium; a first-order block's stress is
// its mean), and the base carries the whole column, n·ρ·g·1 m. Settling's
// criterion (unbalanced force ≤ 1e-5 of a block weight) leaves the slow
// modes of the column short of equilibrium by a few 1e-5 of the stress:
// tolerance 1e-4 of each. After it the stack is at rest, the time has not
// moved, and displacements count from the settled state; a second of the
// dynamic run then moves its top by less than 1e-4 of ρ·g·n²h²/(2E), the
// settlement of the column that gravity switched on at once would set
// ringing.
TEST_F(Guidance, SettlingAStackGivesItsLithostaticStress) {
  run("n = 10\n"
      "m = dda.model{ plane = 'strain', gravity = {0, -9.81} }\n"
      "rock = m:rock{ density = 2500, E = 10e9, nu = 0.25 }\n"
      "joint = m:joint{ friction = 30 }\n"
      "base = m:add_block{ {-1, -1}, {2, -1}, {2, 0}, {-1, 0}, rock = rock, joint = joint }\n"
      "base:fix()\n"
      "stack = {}\n"
      "for k = 1, n do stack[k] = m:add_block{ {0, k - 1}, {1, k - 1}, {1, k}, {0, k}, rock = rock, joint = joint } "
      "end\n"
      "top = m:monitor{ at = {0.5, n - 0.5}, fields = {'uy', 'vy'}, csv = false }\n"
      "info = m:settle{}\n"
      "steps, ratio, t = info.steps, info.ratio, m:time()\n"
      "worst = 0\n"
      "for k = 1, n do\n"
      "  local _, syy = stack[k]:stress()\n"
      "  local expected = -2500 * 9.81 * (n - (k - 0.5))\n"
      "  worst = math.max(worst, math.abs(syy - expected) / math.abs(expected))\n"
      "end\n"
      "base_force = 0\n"
      "for _, c in ipairs(m:contacts{ block = base }) do base_force = base_force + c.normal_force end\n"
      "speed = 0\n"
      "for k = 1, n do local vx, vy, w = stack[k]:velocity() speed = math.max(speed, math.abs(vx), math.abs(vy)) end\n"
      "ux, uy = stack[n]:displacement()\n"
      "top_uy = top:value('uy')\n"
      "m:run{ time = 1 }\n"
      "moved = math.abs(top:peak('uy'))\n");
  std::printf(
      "stack of 10 settled in %g steps (unbalanced force %.3g of a block weight); σyy worst %.3g of ρ·g·depth; "
      "base %.6g N against %.6g N\n",
      number("steps"), number("ratio"), number("worst"), std::fabs(number("base_force")), 10 * 2500 * kG);
  EXPECT_LE(number("ratio"), 1e-5);
  EXPECT_LT(number("worst"), 1e-4);
  EXPECT_NEAR(std::fabs(number("base_force")), 10 * 2500 * kG, 1e-4 * 10 * 2500 * kG);
  EXPECT_EQ(number("t"), 0);
  EXPECT_EQ(number("speed"), 0);
  EXPECT_EQ(number("ux"), 0);
  EXPECT_EQ(number("uy"), 0);
  EXPECT_EQ(number("top_uy"), 0);
  EXPECT_LT(number("moved"), 1e-4 * 2500 * kG * 10 * 10 / (2 * 10e9));
}

// A block on a 40° incline with φ = 20° cannot stand: settling says so,
// naming the block, instead of handing a sliding model to the dynamic run.
TEST_F(Guidance, SettlingRefusesAModelThatDoesNotStand) {
  run("m = dda.model{ plane = 'stress', gravity = {9.81 * math.sin(math.rad(40)), -9.81 * math.cos(math.rad(40))} }\n"
      "rock = m:rock{ density = 2500, E = 10e9, nu = 0.25 }\n"
      "joint = m:joint{ friction = 20 }\n"
      "base = m:add_block{ {-2, -1}, {3, -1}, {3, 0}, {-2, 0}, rock = rock, joint = joint }\n"
      "base:fix()\n"
      "m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1}, rock = rock, joint = joint }\n");
  const std::string e = error_of("m:settle{ max_steps = 50 }");
  EXPECT_NE(e.find("m:settle: not in equilibrium after 50 steps: the unbalanced force on block 1"), std::string::npos)
      << e;
}

// A block thrown with (vx, vy) = (3, 4) m/s under gravity, no contacts:
// v(t) = (3, 4 − g·t), u(t) = (3t, 4t − g·t²/2), exact in DDA (constant
// acceleration). The peaks over the recorded rows, of |v| (monitor:ppv,
// monitor:peak("velocity")) and of |u| (monitor:peak("displacement")), are
// the closed form's largest over the same times: tolerance 1e-9 of each.
TEST_F(Guidance, PeaksOfVectorFieldsOfAThrownBlock) {
  run("m = dda.model{ plane = 'stress', gravity = {0, -9.81}, g1 = 0.01 }\n"
      "m:rock{ density = 2000, E = 1e9, nu = 0.2 }\n"
      "b = m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\n"
      "b:set_velocity(3, 4)\n"
      "mon = m:monitor{ at = {0.5, 0.5}, fields = {'vx', 'vy', 'ux', 'uy'}, csv = false }\n"
      "half = m:monitor{ at = {0.5, 0.5}, fields = {'vx'}, csv = false }\n"
      "m:run{ time = 1 }\n"
      "ppv, ppv_t, ppv_x, ppv_y = mon:ppv()\n"
      "pv = mon:peak('velocity')\n"
      "pu, pu_t = mon:peak('displacement')\n"
      "best_v, best_u = 0, 0\n"
      "for _, t in ipairs(mon:times()) do\n"
      "  best_v = math.max(best_v, math.sqrt(9 + (4 - 9.81 * t)^2))\n"
      "  best_u = math.max(best_u, math.sqrt((3 * t)^2 + (4 * t - 9.81 * t * t / 2)^2))\n"
      "end\n");
  const double t = number("ppv_t");
  EXPECT_NEAR(number("ppv"), number("best_v"), 1e-9 * number("best_v"));
  EXPECT_NEAR(number("ppv"), std::hypot(3, 4 - kG * t), 1e-9 * number("ppv"));
  EXPECT_NEAR(number("ppv_x"), 3, 1e-9);
  EXPECT_NEAR(number("ppv_y"), 4 - kG * t, 1e-9);
  EXPECT_EQ(number("pv"), number("ppv"));
  EXPECT_NEAR(number("pu"), number("best_u"), 1e-9 * number("best_u"));
  // A monitor without both components names what it lacks.
  EXPECT_NE(error_of("half:ppv()").find("does not record 'vy', which 'velocity' needs"), std::string::npos);
}

}  // namespace
