// Contact forces and N_c as fix tfdem/coupling samples them in a running LIGGGHTS (1 and 2
// ranks), on a hand-built packing whose forces are known by hand: a chain of four 4 mm spheres
// along x with overlaps of 1 %, 2 % and 0.5 % of d (linear springs, k_n = 1000 N/m, no
// damping), a sphere resting 1 % of d into the floor (wall k_n = 2000 N/m) and a loner. On 2
// ranks (processors 2 1 1 over x in [0, 0.1]) the chain's middle pair straddles x = 0.05.
// Sampled after one step of 1e-8 s, when the particles have moved ~1e-13 m.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "dem_instance.h"
#include "tfdem/analysis.h"

namespace {

constexpr double kDiameter = 0.004, kStiffness = 1000.0, kWallStiffness = 2000.0;

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// Particle positions (x, y) at z = 0.005, IDs 1..6 in this order.
struct Layout {
  std::vector<double> x, y;
  double overlap[3] = {0.01 * kDiameter, 0.02 * kDiameter, 0.005 * kDiameter};
  double floor_overlap = 0.01 * kDiameter;
  Layout() {
    double xi = 0.05 - 1.5 * kDiameter;
    for (int i = 0; i < 4; ++i) {
      x.push_back(xi);
      y.push_back(0.05);
      if (i < 3) xi += kDiameter - overlap[i];
    }
    x.push_back(0.02);  // on the floor
    y.push_back(0.5 * kDiameter - floor_overlap);
    x.push_back(0.08);  // alone
    y.push_back(0.08);
  }
};

std::string script(const Layout &layout, const std::string &dir) {
  const std::string path = dir + "/in.contacts";
  std::ofstream out(path);
  out << "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n"
      << "communicate single vel yes\nunits si\nprocessors * 1 1\n"
      << "region box block 0 0.1 0 0.1 0 0.01 units box\ncreate_box 2 box\n"
      << "neighbor 0.002 bin\nneigh_modify delay 0\n"
      << "fix m1 all property/global kn peratomtypepair 2 " << kStiffness << " " << kWallStiffness << " "
      << kWallStiffness << " " << kWallStiffness << "\n"
      << "fix m2 all property/global kt peratomtypepair 2 100 100 100 100\n"
      << "fix m3 all property/global gamman_abs peratomtypepair 2 0 0 0 0\n"
      << "fix m4 all property/global gammat_abs peratomtypepair 2 0 0 0 0\n"
      << "fix m5 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5\n"
      << "pair_style gran model hooke/stiffness tangential history absolute_damping on\npair_coeff * *\n"
      << "timestep 1e-8\n";
  for (std::size_t i = 0; i < layout.x.size(); ++i)
    out << "create_atoms 1 single " << layout.x[i] << " " << layout.y[i] << " 0.005 units box\n";
  out.precision(17);
  out << "set atom * diameter " << kDiameter << " density 2500\n"
      << "fix floor all wall/gran model hooke/stiffness tangential history primitive type 2 yplane 0 "
         "absolute_damping on\n"
      << "fix grav all gravity 9.81 vector 0 -1 0\nfix fluid all tfdem/coupling\nfix integr all nve/sphere\n";
  return path;
}

TEST(ContactSample, HandBuiltPackingOnEveryRank) {
  const Layout layout;
  const std::string dir = std::getenv("TFDEM_TEST_DIR") ? std::getenv("TFDEM_TEST_DIR") : ".";
  std::string path;
  if (rank() == 0) path = script(layout, dir);
  MPI_Barrier(MPI_COMM_WORLD);
  tfdem::DemInstance dem(MPI_COMM_WORLD, dir + "/in.contacts", dir + "/log.contacts");
  dem.run(1, true);
  std::vector<double> force;
  std::vector<int> coordination;
  dem.contact_sample(force, coordination);

  // By hand: chain forces along x from the springs k delta, the floor particle's wall force
  // up; gravity is not a contact force.
  const double f1 = kStiffness * layout.overlap[0], f2 = kStiffness * layout.overlap[1],
               f3 = kStiffness * layout.overlap[2];
  std::map<int, std::vector<double>> expected_force = {
      {1, {-f1, 0, 0}}, {2, {f1 - f2, 0, 0}}, {3, {f2 - f3, 0, 0}}, {4, {f3, 0, 0}},
      {5, {0, kWallStiffness * layout.floor_overlap, 0}}, {6, {0, 0, 0}}};
  std::map<int, int> expected_coordination = {{1, 1}, {2, 2}, {3, 2}, {4, 1}, {5, 0}, {6, 0}};
  const double scale = f2;
  for (std::size_t i = 0; i < dem.local_count(); ++i) {
    const int id = dem.tags()[i];
    EXPECT_EQ(coordination[i], expected_coordination[id]) << "particle " << id << " on rank " << rank();
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(force[3 * i + k], expected_force[id][k], 1e-6 * scale) << "particle " << id << " axis " << k;
  }
  // The middle pair straddles the ranks' boundary on 2 ranks: each particle still counts it once.
  tfdem::analysis::ContactCounts counts = tfdem::analysis::contact_counts(coordination.data(), coordination.size());
  double sums[4] = {counts.particles, counts.contacts, counts.in_contact, counts.multi};
  MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const tfdem::analysis::ContactCounts all{sums[0], sums[1], sums[2], sums[3]};
  EXPECT_EQ(all.particles, 6.0);
  EXPECT_DOUBLE_EQ(all.bulk_coordination(), 6.0 / 6.0);
  EXPECT_DOUBLE_EQ(all.multicontact(), 2.0 / 4.0);
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size == 2) {  // the split is real: particles 2 and 3 on different ranks
    int has[2] = {0, 0};
    for (std::size_t i = 0; i < dem.local_count(); ++i) {
      if (dem.tags()[i] == 2) has[0] = rank() + 1;
      if (dem.tags()[i] == 3) has[1] = rank() + 1;
    }
    MPI_Allreduce(MPI_IN_PLACE, has, 2, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    EXPECT_NE(has[0], has[1]);
  }
}

}  // namespace

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int failed = RUN_ALL_TESTS();
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return failed;
}
