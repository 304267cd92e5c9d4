// LIGGGHTS 3.8.0 keeps its fix style table (Modify::fix_map) private and offers no plug-in
// hook. Explicit instantiation of a template may name private members, so a member-pointer
// accessor built that way reaches the table in standard C++ without patching LIGGGHTS.
#include <map>
#include <string>

#include "fix_tfdem_coupling.h"
#include "lammps.h"
#include "modify.h"
#include "tfdem_liggghts.h"

namespace {

using FixFactory = LAMMPS_NS::Fix *(*)(LAMMPS_NS::LAMMPS *, int, char **);
using FixMap = std::map<std::string, FixFactory>;

struct ModifyFixMapTag {
  using type = FixMap *LAMMPS_NS::Modify::*;
  friend type member_pointer(ModifyFixMapTag);
};

template <typename Tag, typename Tag::type Member>
struct PrivateMemberAccess {
  friend typename Tag::type member_pointer(Tag) { return Member; }
};

template struct PrivateMemberAccess<ModifyFixMapTag, &LAMMPS_NS::Modify::fix_map>;

// Factory with the signature LIGGGHTS expects for a fix style.
template <typename FixClass>
LAMMPS_NS::Fix *create_fix(LAMMPS_NS::LAMMPS *lmp, int narg, char **arg) {
  return new FixClass(lmp, narg, arg);
}

}  // namespace

namespace tfdem {

void register_fix_styles(LAMMPS_NS::LAMMPS *lmp) {
  FixMap &styles = *(lmp->modify->*member_pointer(ModifyFixMapTag{}));
  styles["tfdem/coupling"] = &create_fix<LAMMPS_NS::FixTfdemCoupling>;
}

}  // namespace tfdem
