// Islands shared out among the workers (dynamics/detail/contact_groups.hpp):
// whole islands to each group, every body the solve changes in exactly one
// group and the bodies at rest in none, the groups within their bound of
// an even share or no split at all; and an island's contacts colored alone
// come out in the colors and the order they take among all the contacts.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "impulse/dynamics/detail/constraint_graph.hpp"
#include "impulse/dynamics/detail/contact_groups.hpp"

namespace dynamics_contact_groups_tests {

namespace {

using namespace impulse;
using impulse::detail::contact_groups;

solver_body<float> moving() {
  solver_body<float> b;
  b.inverse_mass = 1;
  b.inverse_inertia = mat3<float>::diagonal({6, 6, 6});
  return b;
}

contact_constraint<float> between(std::uint32_t a, std::uint32_t b) {
  contact_constraint<float> c;
  c.body_a = a, c.body_b = b;
  return c;
}

/// Checks what every split must hold: each contact in one group, in the
/// contacts' order; each of its bodies that is not at rest in that group;
/// each such body in exactly one group; the bodies at rest in none.
void check_split(const contact_groups& groups, std::span<const solver_body<float>> bodies,
                 std::span<const contact_constraint<float>> contacts) {
  std::vector<int> contact_group(contacts.size(), -1), body_group(bodies.size(), -1);
  for (std::uint32_t g = 0; g < groups.size(); ++g) {
    const auto mine = groups.contacts(g);
    CHECK(std::is_sorted(mine.begin(), mine.end()));
    for (const std::uint32_t k : mine) {
      CHECK(contact_group[k] == -1);
      contact_group[k] = int(g);
    }
    for (const std::uint32_t i : groups.bodies(g)) {
      CHECK(body_group[i] == -1);
      body_group[i] = int(g);
    }
  }
  for (const std::uint32_t i : groups.fixed_bodies()) {
    CHECK(contact_groups::fixed(bodies[i]));
    CHECK(body_group[i] == -1);
    body_group[i] = -2;
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) CHECK(body_group[i] != -1);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    REQUIRE(contact_group[k] >= 0);
    for (const std::uint32_t i : {contacts[k].body_a, contacts[k].body_b})
      if (!contact_groups::fixed(bodies[i])) CHECK(body_group[i] == contact_group[k]);
  }
}

}  // namespace

TEST_CASE("columns on the ground are shared out whole, a moving platform joins the two it carries") {
  // Body 0 the ground, at rest; 20 columns of 3 boxes, each on the ground
  // and on one another (3 contacts a column); body 61 a kinematic
  // platform moving under the tops of columns 5 and 6; 62 and 63 free.
  std::vector<solver_body<float>> bodies(64, moving());
  bodies[0] = solver_body<float>{};
  bodies[61] = solver_body<float>{};
  bodies[61].linear_velocity = {1, 0, 0};
  std::vector<contact_constraint<float>> contacts;
  for (std::uint32_t c = 0; c < 20; ++c) {
    const std::uint32_t base = 1 + 3 * c;
    contacts.push_back(between(0, base));
    contacts.push_back(between(base, base + 1));
    contacts.push_back(between(base + 1, base + 2));
  }
  contacts.push_back(between(61, 1 + 3 * 5 + 2));
  contacts.push_back(between(1 + 3 * 6 + 2, 61));
  CHECK_FALSE(contact_groups::fixed(bodies[61]));
  contact_groups groups;
  for (const std::uint32_t count : {2u, 3u, 4u}) {
    CAPTURE(count);
    REQUIRE(groups.split(std::span<const solver_body<float>>(bodies),
                         std::span<const contact_constraint<float>>(contacts), count));
    CHECK(groups.size() == count);
    check_split(groups, bodies, contacts);
    CHECK(groups.fixed_bodies().size() == 1);
    CHECK(groups.fixed_bodies()[0] == 0);
    // Within 1.15 of an even share, and the islands in the order of their
    // first contact: a column's group never falls below the one before.
    std::size_t heaviest = 0;
    for (std::uint32_t g = 0; g < count; ++g) heaviest = std::max(heaviest, groups.contacts(g).size());
    CHECK(double(heaviest) * count <= contact_groups::most_uneven * double(contacts.size()));
    std::vector<int> column_group(20);
    for (std::uint32_t g = 0; g < count; ++g)
      for (const std::uint32_t k : groups.contacts(g))
        if (k < 60) column_group[k / 3] = int(g);
    CHECK(std::is_sorted(column_group.begin(), column_group.end()));
    CHECK(column_group[5] == column_group[6]);  // joined through the platform
  }
}

TEST_CASE("one island, or a body in more than 64 contacts, is not split") {
  std::vector<solver_body<float>> bodies(200, moving());
  bodies[0] = solver_body<float>{};
  contact_groups groups;
  SUBCASE("a chain of 100 boxes is one island") {
    std::vector<contact_constraint<float>> chain;
    for (std::uint32_t i = 0; i < 100; ++i) chain.push_back(between(i, i + 1));
    CHECK_FALSE(groups.split(std::span<const solver_body<float>>(bodies),
                             std::span<const contact_constraint<float>>(chain), 2));
    CHECK(groups.size() == 0);
  }
  SUBCASE("two even islands, one a body touching `leaves` others") {
    for (const std::uint32_t leaves : {64u, 65u}) {
      CAPTURE(leaves);
      std::vector<contact_constraint<float>> contacts;
      for (std::uint32_t i = 0; i < leaves; ++i) contacts.push_back(between(1, 2 + i));
      for (std::uint32_t i = 0; i < leaves; ++i) contacts.push_back(between(100 + i, 101 + i));
      // A contact whose bodies have 65 contacts between them always takes
      // a color; with 66 it may be left over, solved alone, and the
      // islands stay together.
      const bool split = groups.split(std::span<const solver_body<float>>(bodies),
                                      std::span<const contact_constraint<float>>(contacts), 2);
      CHECK(split == (leaves == 64));
      if (split) check_split(groups, bodies, contacts);
    }
  }
  SUBCASE("a contact between two bodies at rest joins no island, and goes to a group") {
    std::vector<contact_constraint<float>> contacts;
    for (std::uint32_t i = 1; i < 41; i += 2) contacts.push_back(between(i, i + 1));
    bodies[150] = solver_body<float>{};
    contacts.push_back(between(0, 150));  // the ground and a kinematic body standing on it
    REQUIRE(groups.split(std::span<const solver_body<float>>(bodies),
                         std::span<const contact_constraint<float>>(contacts), 2));
    check_split(groups, bodies, contacts);
    CHECK(groups.fixed_bodies().size() == 2);
  }
  SUBCASE("no workers to share among, or no contacts") {
    const std::vector<contact_constraint<float>> one{between(1, 2), between(3, 4)};
    CHECK_FALSE(groups.split(std::span<const solver_body<float>>(bodies),
                             std::span<const contact_constraint<float>>(one), 1));
    CHECK_FALSE(groups.split(std::span<const solver_body<float>>(bodies), std::span<const contact_constraint<float>>(),
                             2));
  }
}

TEST_CASE("an island's contacts colored alone take the colors and the order they take among all") {
  // 12 towers of 6 boxes on the ground, their contacts given interleaved
  // (tower by tower would be too kind): each tower its own island.
  std::vector<solver_body<float>> bodies(1 + 12 * 6, moving());
  bodies[0] = solver_body<float>{};
  std::vector<contact_constraint<float>> contacts;
  for (std::uint32_t level = 0; level < 6; ++level)
    for (std::uint32_t t = 0; t < 12; ++t) {
      const std::uint32_t box = 1 + 6 * t + level;
      contacts.push_back(between(level == 0 ? 0 : box - 1, box));
      if (level >= 2 && t % 3 == 0) contacts.push_back(between(box - 2, box));  // a second contact two down
    }
  contact_groups groups;
  REQUIRE(groups.split(std::span<const solver_body<float>>(bodies), std::span<const contact_constraint<float>>(contacts),
                       3));
  detail::constraint_graph whole, part;
  const auto all = std::span<const contact_constraint<float>>(contacts);
  whole.build(std::span<const solver_body<float>>(bodies), all, 4);
  // Each color's contacts, in order, as the whole graph has them.
  const auto colors_of = [](const detail::constraint_graph& g) {
    std::vector<std::vector<std::uint32_t>> colors(g.color_count());
    for (std::size_t q = 0; q < g.color_count(); ++q)
      for (std::uint32_t k = g.first_batch(q); k < g.first_batch(q + 1); ++k)
        for (const std::uint32_t i : g.batch(k)) colors[q].push_back(i);
    return colors;
  };
  const std::vector<std::vector<std::uint32_t>> every = colors_of(whole);
  CHECK(every.size() >= 2);
  for (std::uint32_t g = 0; g < groups.size(); ++g) {
    CAPTURE(g);
    const auto mine = groups.contacts(g);
    part.build(std::span<const solver_body<float>>(bodies), all, mine, 4);
    std::vector<std::vector<std::uint32_t>> expected;
    for (const std::vector<std::uint32_t>& color : every) {
      std::vector<std::uint32_t> kept;
      for (const std::uint32_t i : color)
        if (std::find(mine.begin(), mine.end(), i) != mine.end()) kept.push_back(i);
      if (!kept.empty()) expected.push_back(kept);
    }
    CHECK(colors_of(part) == expected);
    CHECK(part.leftover().empty());
  }
}

TEST_CASE("a split asked again of the same contacts keeps its groups, and one of changed contacts or bodies is redone") {
  // Ten columns of two boxes on the ground (body 0): ten islands of two
  // contacts each, split in two groups of five columns.
  const auto columns = [] {
    std::vector<contact_constraint<float>> contacts;
    for (std::uint32_t c = 0; c < 10; ++c) {
      contacts.push_back(between(0, 1 + 2 * c));
      contacts.push_back(between(1 + 2 * c, 2 + 2 * c));
    }
    return contacts;
  };
  std::vector<solver_body<float>> bodies(21, moving());
  bodies[0] = solver_body<float>{};
  std::vector<contact_constraint<float>> contacts = columns();
  contact_groups groups, fresh;
  const auto split = [&](contact_groups& g) {
    return g.split(std::span<const solver_body<float>>(bodies), std::span<const contact_constraint<float>>(contacts), 2);
  };
  const auto same_groups = [](const contact_groups& x, const contact_groups& y) {
    if (x.size() != y.size()) return false;
    for (std::uint32_t g = 0; g < x.size(); ++g) {
      const auto cx = x.contacts(g), cy = y.contacts(g), bx = x.bodies(g), by = y.bodies(g);
      if (!std::equal(cx.begin(), cx.end(), cy.begin(), cy.end()) || !std::equal(bx.begin(), bx.end(), by.begin(), by.end()))
        return false;
    }
    const auto fx = x.fixed_bodies(), fy = y.fixed_bodies();
    return std::equal(fx.begin(), fx.end(), fy.begin(), fy.end());
  };
  REQUIRE(split(groups));
  REQUIRE(groups.contacts(0).size() == 10);
  // Asked again, with the bodies' velocities changed (the split reads only
  // whether a body moves under impulses and whether it is at rest).
  bodies[3].linear_velocity = {0, -1, 0};
  REQUIRE(split(groups));
  REQUIRE(fresh.split(std::span<const solver_body<float>>(bodies), std::span<const contact_constraint<float>>(contacts), 2));
  CHECK(same_groups(groups, fresh));
  SUBCASE("a contact between two columns joins them") {
    contacts.push_back(between(2, 4));  // the tops of columns 0 and 1
    REQUIRE(split(groups));
    REQUIRE(split(fresh = contact_groups{}));
    CHECK(same_groups(groups, fresh));
    check_split(groups, bodies, contacts);
    CHECK(groups.contacts(0).size() == 11);
  }
  SUBCASE("a contact that changes one of its bodies") {
    contacts[19] = between(0, 20);  // the top of the last column on the ground
    REQUIRE(split(groups));
    REQUIRE(split(fresh = contact_groups{}));
    CHECK(same_groups(groups, fresh));
    check_split(groups, bodies, contacts);
  }
  SUBCASE("the ground set moving joins every column in one island: no split") {
    bodies[0].linear_velocity = {1, 0, 0};
    CHECK_FALSE(split(groups));
    CHECK(groups.size() == 0);
    bodies[0].linear_velocity = {};
    REQUIRE(split(groups));
    CHECK(same_groups(groups, fresh));
  }
  SUBCASE("five groups asked for") {
    REQUIRE(groups.split(std::span<const solver_body<float>>(bodies), std::span<const contact_constraint<float>>(contacts), 5));
    CHECK(groups.size() == 5);
    check_split(groups, bodies, contacts);
  }
}

}  // namespace dynamics_contact_groups_tests
