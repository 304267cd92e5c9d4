// LIGGGHTS data files (read_data) as the coupler checks them before LIGGGHTS reads one: an atom
// outside the box its header gives, on a side whose boundary drops atoms (f), makes LIGGGHTS
// stop with "Did not assign all atoms correctly" and no atom named; the coupler names them.
// Atom lines of atom_style sphere / granular: id type diameter density x y z [image flags].
#ifndef TFDEM_DATA_FILE_H
#define TFDEM_DATA_FILE_H

#include <cstddef>
#include <istream>
#include <string>
#include <vector>

namespace tfdem::data_file {

// Which sides of the box drop atoms beyond them, per axis (lower, upper), from a `boundary`
// command's three words (p, f, s, m, or two of them for the two sides: "fm"). Throws
// std::invalid_argument for anything else.
struct Boundary {
  bool drops[3][2] = {{true, true}, {true, true}, {true, true}};  // LIGGGHTS' default: f f f
};
Boundary boundary_from_words(const std::vector<std::string> &words);

// The atoms of the Atoms section LIGGGHTS cannot place: outside the box along a side that
// drops them ("id 17 at (x, y, z) m (line 20): y is above yhi = 0.45 m"), or with a diameter
// or position that is not a finite number (at most `limit`; `count` gets them all). Throws
// std::invalid_argument "file:line: ..." for a header or atom line it cannot read.
// Read from a stream line by line, so that a large file is never held in memory whole.
std::vector<std::string> atoms_outside_box(std::istream &in, const std::string &file, const Boundary &boundary,
                                           std::size_t limit, std::size_t &count);
std::vector<std::string> atoms_outside_box(const std::string &text, const std::string &file, const Boundary &boundary,
                                           std::size_t limit, std::size_t &count);

// The atoms of a data file (atom_style sphere / granular) as a particle engine other than
// LIGGGHTS reads them: the box of its header, its atom type count, and per atom its ID, type,
// diameter, density, position and, from the Velocities section when it has one (id vx vy vz
// wx wy wz), velocity and spin (else zero). Throws std::invalid_argument "file:line: ..." for a
// line it cannot read, an atom count that differs from the header's, or a type beyond it.
struct Atoms {
  double lower[3] = {0, 0, 0}, upper[3] = {0, 0, 0};
  int type_count = 0;
  std::vector<int> id, type;
  std::vector<double> diameter, density;
  std::vector<double> position, velocity, spin;  // 3 per atom
};
Atoms read_atoms(const std::string &text, const std::string &file);

}  // namespace tfdem::data_file

#endif
