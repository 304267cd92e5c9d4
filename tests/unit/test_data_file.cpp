// LIGGGHTS data files: atoms outside the box on sides that drop them, found on a hand-written
// file; periodic and shrink-wrapped sides keep their atoms; the boundary command's styles.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "tfdem/data_file.h"

namespace {

using namespace tfdem::data_file;

const std::string kData =
    "LIGGGHTS data file\n\n3 atoms\n1 atom types\n\n"
    "0 0.15 xlo xhi\n0 0.45 ylo yhi\n0 0.0025 zlo zhi\n\n"
    "Atoms # granular\n\n"
    "1 1 0.0025 2526 0.05 0.10 0.00125 0 0 0\n"
    "2 1 0.0025 2526 0.16 0.10 0.00125\n"
    "3 1 0.0025 2526 0.05 -0.01 0.00125\n\n"
    "Velocities\n\n1 0 0 0 0 0 0\n";

TEST(DataFile, AtomsOutsideFixedSidesAreNamed) {
  std::size_t count = 0;
  const auto outside = atoms_outside_box(kData, "bed.data", Boundary{}, 10, count);
  EXPECT_EQ(count, 2u);
  ASSERT_EQ(outside.size(), 2u);
  EXPECT_EQ(outside[0], "id 2 at (0.16, 0.1, 0.00125) m (line 13): x is above xhi = 0.15 m");
  EXPECT_EQ(outside[1], "id 3 at (0.05, -0.01, 0.00125) m (line 14): y is below ylo = 0 m");
  EXPECT_EQ(atoms_outside_box(kData, "bed.data", Boundary{}, 1, count).size(), 1u);
  EXPECT_EQ(count, 2u);
}

TEST(DataFile, PeriodicAndShrinkWrappedSidesKeepTheirAtoms) {
  std::size_t count = 0;
  const Boundary b = boundary_from_words({"p", "mf", "f"});
  EXPECT_FALSE(b.drops[0][0]);
  EXPECT_FALSE(b.drops[1][0]);
  EXPECT_TRUE(b.drops[1][1]);
  EXPECT_TRUE(atoms_outside_box(kData, "bed.data", b, 10, count).empty());
  EXPECT_EQ(count, 0u);
  EXPECT_THROW(boundary_from_words({"f", "x", "f"}), std::invalid_argument);
  EXPECT_THROW(boundary_from_words({"f", "f"}), std::invalid_argument);
}

TEST(DataFile, NonFiniteAtomIsNamed) {
  std::size_t count = 0;
  const auto bad = atoms_outside_box("t\n\n0 1 xlo xhi\n\nAtoms\n\n4 1 0.002 2500 nan 0.5 0\n", "bed.data",
                                     Boundary{}, 10, count);
  ASSERT_EQ(bad.size(), 1u);
  EXPECT_EQ(bad[0], "id 4 (line 7): its diameter or position is not a finite number ('4 1 0.002 2500 nan 0.5 0')");
}

TEST(DataFile, AtomsReadWithTheirVelocities) {
  const Atoms a = read_atoms(kData, "bed.data");
  EXPECT_EQ(a.type_count, 1);
  EXPECT_EQ(a.upper[0], 0.15);
  EXPECT_EQ(a.upper[1], 0.45);
  ASSERT_EQ(a.id, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(a.diameter[2], 0.0025);
  EXPECT_EQ(a.density[0], 2526);
  EXPECT_EQ(a.position[3], 0.16);  // atom 2's x
  EXPECT_EQ(a.velocity, std::vector<double>(9, 0.0));  // atom 1's row holds zeros; 2 and 3 have none
  const Atoms b = read_atoms(kData + std::string("2 0.1 -0.2 0 0 0 5\n"), "bed.data");
  EXPECT_EQ(b.velocity[4], -0.2);
  EXPECT_EQ(b.spin[5], 5);
  EXPECT_THROW(read_atoms(kData.substr(0, kData.find("3 1 0.0025")), "bed.data"), std::invalid_argument);  // 2 of 3
}

TEST(DataFile, UnreadableAtomLineIsNamed) {
  std::size_t count = 0;
  try {
    atoms_outside_box("t\n\n0 1 xlo xhi\n\nAtoms\n\n1 1 0.002 x 0 0 0\n", "bed.data", Boundary{}, 10, count);
    FAIL() << "no exception";
  } catch (const std::invalid_argument &e) {
    EXPECT_NE(std::string(e.what()).find("bed.data:7: cannot read an atom"), std::string::npos) << e.what();
  }
}

}  // namespace
