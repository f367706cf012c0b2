// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The contact laws behind one interface (contact/contact_model.hpp): each
// control a law declares it does not read changes nothing under it, and the
// scene the test runs is one in which that control does change the answer
// under a law that reads it (so the test could fail). Reference: the state
// hash of the run with the control at its default; tolerance: none (the same
// bits).
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include <tbb/task_arena.h>

#include "../scenes.hpp"
#include "contact/contact_detection.hpp"
#include "contact/contact_model.hpp"
#include "core/parallel.hpp"
#include "world/controls.hpp"

using namespace dda;

namespace {

// Every law, in the order of the control contact_law's choices.
std::vector<ContactLaw> every_law() {
  std::vector<ContactLaw> laws;
  for (std::size_t i = 0; i < find_control("contact_law")->choices.size(); ++i)
    laws.push_back(static_cast<ContactLaw>(i));
  return laws;
}

const char* name(ContactLaw law) { return find_control("contact_law")->choices[static_cast<int>(law)]; }

// A settling wall(3) with velocity carried over (gg = 1: contacts open and
// close, slide and lock) and a block landing on an incline beside it, under
// `law` with the number control `control` at `value` (nullptr: every control
// at its default): its state hash after 40 steps.
std::uint64_t run_hash(ContactLaw law, const char* control, double value) {
  World w = test::brick_wall(3);
  Controls& c = w.controls();
  c.gg = 1;
  c.threads = 1;
  c.contact_law = law;
  if (control) find_control(control)->number(c) = value;
  const int rock = w.add_rock_material(test::granite());
  test::add_fixed_base(w, test::rotated(test::rectangle(10, -1, 6, 1), 0.3), rock);
  w.add_block(test::rotated(test::rectangle(12, 0.01, 1, 0.5), 0.3), rock);
  for (int k = 0; k < 40; ++k) w.step();
  return w.state_hash();
}

TEST(ContactModel, EachLawIsItsOwnModel) {
  for (const ContactLaw law : every_law()) EXPECT_EQ(make_contact_model(law)->law(), law) << name(law);
}

// A control a law declares it does not read is refused under that law (the
// step's start names it and the law, world/inert_controls.hpp), and moves the
// answer under a law that reads it.
TEST(ContactModel, AControlALawDoesNotReadIsRefusedUnderIt) {
  int declared = 0;
  for (const ContactLaw law : every_law()) {
    for (const IgnoredControl& ignored : make_contact_model(law)->ignored_controls()) {
      ++declared;
      const ControlSpec* spec = find_control(ignored.control);
      ASSERT_TRUE(spec && spec->type == ControlType::Number) << ignored.control << " is not a number control";
      EXPECT_TRUE(std::string(ignored.why).size() > 10) << ignored.control << ": say why";
      Controls defaults;
      const double changed = spec->number(defaults) > 0 ? 1000 * spec->number(defaults) : 1e-3;
      try {
        run_hash(law, ignored.control, changed);
        ADD_FAILURE() << ignored.control << " = " << changed << " under \"" << name(law) << "\" was not refused";
      } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(ignored.control), std::string::npos) << what;
        EXPECT_NE(what.find(msg("contact_law = \"", name(law), "\"")), std::string::npos) << what;
      }
      // Under a law that reads it, the same change moves the answer.
      for (const ContactLaw other : every_law()) {
        bool reads = true;
        for (const IgnoredControl& o : make_contact_model(other)->ignored_controls())
          reads = reads && std::string(o.control) != ignored.control;
        if (reads) {
          EXPECT_NE(run_hash(other, ignored.control, changed), run_hash(other, nullptr, 0))
              << ignored.control << " = " << changed << " under \"" << name(other) << "\"";
        }
      }
    }
  }
  EXPECT_GT(declared, 0);  // (the holding law's contact_tolerance)
}

// A law's per-contact history follows the contacts into the model of
// another law where it means the same: the friction lag's memory (both
// penalty laws keep it) of a block sliding on 40° / φ = 25° (gravity on at
// once, friction_lag = 3 ms, 30 steps of 1e-4 s under "holding"), then one
// step under "shi": each contact closed through it is one step older.
// Reference: its age before plus the step's Δt, exactly; a memory dropped
// at the switch would be a new interface, its age the step's Δt alone.
TEST(ContactModel, TheHistoryFollowsTheContactsIntoAnotherLaw) {
  World w;
  test::block_on_incline(w, deg_to_rad(40), 25);
  Controls& c = w.controls();
  c.contact_law = ContactLaw::Holding;
  c.friction_lag = 3e-3;
  c.g1 = 1e-4;
  for (int k = 0; k < 30; ++k) w.step();
  std::vector<double> age;
  for (std::size_t i = 0; i < w.contacts().size(); ++i) age.push_back(test::friction_memory(w, i).age);
  c.contact_law = ContactLaw::Shi;
  const StepStats step = w.step();
  ASSERT_EQ(w.contact_model()->law(), ContactLaw::Shi);
  ASSERT_FALSE(step.contacts_searched);
  ASSERT_EQ(step.step_cuts, 0);
  int closed = 0;
  for (std::size_t i = 0; i < w.contacts().size(); ++i) {
    if (w.contacts()[i].state == ContactState::Open || !(age[i] > 0)) continue;
    ++closed;
    EXPECT_EQ(test::friction_memory(w, i).age, age[i] + step.dt) << "contact " << i;
  }
  EXPECT_GE(closed, 1);
}

// The contacts' energy terms (ContactModel::energy, made in parallel) are
// the serial loop's sums in contact order, bit for bit, for any thread count.
// Reference: that loop, written out here (½N²/k_n and, locked, ½S²/k_s
// held; −|S·ds| by friction, sliding); tolerance: none (the same bits). The
// contacts' forces span nine decades, so another order of the sums (the
// fixed chunks' partial sums, checked below) gives other bits: the test
// could fail.
TEST(ContactModel, EnergyIsTheSerialSumInContactOrderForAnyThreadCount) {
  constexpr int kBlocks = 400, kContacts = 5000;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  const JointMaterial joints[] = {JointMaterial{30, 0, 0, 0, 0}, JointMaterial{25, 0, 0, 4e9, 0}};
  ContactParameters p;
  p.g0 = 1e10;
  p.shear_ratio = 0.4;
  p.joints = joints;
  std::vector<Contact> contacts(kContacts);
  ContactLinearisation lin;
  lin.gradients.resize(kContacts);
  for (int i = 0; i < kContacts; ++i) {
    Contact& c = contacts[i];
    c.vblock = static_cast<BlockId>(random() % kBlocks);
    c.eblock = static_cast<BlockId>(random() % kBlocks);
    c.joint = static_cast<std::int32_t>(random() % 2);
    c.length = unit(random) < 0.5 ? 0.0 : 0.1 + unit(random);
    c.scale = 0.5 + unit(random);
    c.state = static_cast<ContactState>(random() % 3);
    c.normal_force = std::pow(10.0, 9 * unit(random)) * (unit(random) - 0.5);
    c.shear_force = std::pow(10.0, 9 * unit(random)) * (unit(random) - 0.5);
    for (Vec6* g : {&lin.gradients[i].es_v, &lin.gradients[i].es_e})
      for (int k = 0; k < 6; ++k) (*g)[k] = unit(random) - 0.5;
  }
  VecX d(6 * kBlocks);
  for (Eigen::Index k = 0; k < d.size(); ++k) d[k] = 1e-3 * (unit(random) - 0.5);

  std::vector<double> held_terms, friction_terms;  // in contact order
  for (int i = 0; i < kContacts; ++i) {
    const Contact& c = contacts[i];
    if (c.state == ContactState::Open) continue;
    const ContactParameters::Springs k = p.springs(c);
    held_terms.push_back(0.5 * c.normal_force * c.normal_force / (c.scale * k.kn));
    if (c.state == ContactState::Locked) {
      held_terms.push_back(0.5 * c.shear_force * c.shear_force / (c.scale * k.ks));
    } else {
      const ContactGradients& g = lin.gradients[i];
      const double ds = g.es_v.dot(d.segment<6>(6 * c.vblock)) + g.es_e.dot(d.segment<6>(6 * c.eblock));
      friction_terms.push_back(std::abs(c.shear_force * ds));
    }
  }
  ContactEnergy serial;
  for (const double t : held_terms) serial.held += t;
  for (const double t : friction_terms) serial.friction -= t;
  ASSERT_GT(friction_terms.size(), 1000u);
  // Another order: the fixed chunks' partial sums, added in chunk order.
  double chunked = 0;
  for (std::size_t c = 0; c < chunk_count(held_terms.size()); ++c) {
    double partial = 0;
    for (std::size_t i = c * kChunk; i < std::min(held_terms.size(), (c + 1) * kChunk); ++i) partial += held_terms[i];
    chunked += partial;
  }
  ASSERT_NE(chunked, serial.held) << "the terms do not tell one order of summation from another";

  for (const ContactLaw law : every_law()) {
    for (const int threads : {1, 2, 4}) {
      const std::unique_ptr<ContactModel> model = make_contact_model(law);
      model->set_parameters(p);
      ContactEnergy e;
      tbb::task_arena(threads).execute([&] { e = model->energy(contacts, lin, d); });
      EXPECT_EQ(std::memcmp(&e.held, &serial.held, sizeof(double)), 0) << name(law) << ", " << threads << " threads";
      EXPECT_EQ(std::memcmp(&e.friction, &serial.friction, sizeof(double)), 0)
          << name(law) << ", " << threads << " threads";
    }
  }
}

}  // namespace

namespace {
// The message a block on a base under `set` refuses at its first step with
// (empty: none).
std::string refusal(void (*set)(Controls&)) {
  World w;
  const int rock = w.add_rock_material(test::granite());
  test::add_fixed_base(w, test::rectangle(0, -1, 4, 1), rock);
  w.add_block(test::rectangle(1, 0.01, 1, 0.5), rock);
  w.controls().gravity = Vec2(0, -9.81);
  set(w.controls());
  try {
    w.step();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

// Controls the model in use does not read are refused at the step's start,
// naming the control, why and the cure (world/inert_controls.hpp); set where
// they are read, or at a value that is what the model does, they pass.
TEST(InertControls, AreRefusedWithTheReasonAndTheCure) {
  struct Case {
    void (*set)(Controls&);
    const char* says;  // "" for a setting that must pass
  };
  const Case cases[] = {
      {[](Controls& c) { c.rho_inf = 0.5; }, "rho_inf = 0.5 is not read here: only integrator = \"generalized_alpha\""},
      {[](Controls& c) {
         c.rho_inf = 0.5;
         c.integrator = Integrator::GeneralizedAlpha;
       },
       ""},
      {[](Controls& c) {
         c.solver.kind = SolverKind::Pcg;
         c.solver.cholmod.refactor_iterations = 3;
       },
       "refactor_iterations = 3 is not read here"},
      {[](Controls& c) {
         c.solver.kind = SolverKind::Pcg;
         c.solver.cholmod.ordering = FillOrdering::Amd;
       },
       "fill_ordering = \"amd\" is not read here"},
      {[](Controls& c) { c.solver.cholmod.ordering = FillOrdering::Amd; }, ""},
      {[](Controls& c) { c.mesh_mass = MeshMass::Lumped; }, "mesh_mass = \"lumped\" is not read here"},
      {[](Controls& c) { c.mesh_mass = MeshMass::Consistent; }, ""},
      {[](Controls& c) { c.solver.mesh_preconditioner = MeshPreconditioning::NodeJacobi; },
       "mesh_preconditioner = \"node_jacobi\" is not read here"},
  };
  for (const Case& k : cases) {
    const std::string said = refusal(k.set);
    if (std::string(k.says).empty()) {
      EXPECT_EQ(said, "");
    } else {
      EXPECT_NE(said.find(k.says), std::string::npos) << said;
      EXPECT_NE(said.find("; remove it"), std::string::npos) << said;
    }
  }
}
