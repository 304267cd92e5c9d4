// Registration of TFDEM's fix styles into a LIGGGHTS instance built outside LIGGGHTS.
#ifndef TFDEM_LIGGGHTS_H
#define TFDEM_LIGGGHTS_H

namespace LAMMPS_NS {
class LAMMPS;
}

namespace tfdem {

// Add every TFDEM fix style to lmp's fix style table. Call after constructing the instance
// and after every `clear` (which rebuilds the table), before the input script uses them.
void register_fix_styles(LAMMPS_NS::LAMMPS *lmp);

}  // namespace tfdem

#endif
