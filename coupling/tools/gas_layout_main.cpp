// tfdem-gas-layout CELLS RANKS: the gas layout the measured rule (tfdem/gas_layout.h) gives a
// mesh of CELLS cells on RANKS ranks: prints `whole` or `split` on stdout and the reason on
// stderr, for launchers (a generated case's Allrun, tfdem.run) that pick the layout.
#include <cstdlib>
#include <iostream>
#include <string>

#include "tfdem/gas_layout.h"

int main(int argc, char *argv[]) {
  const auto whole_number = [](const char *text, long &value) {
    char *end = nullptr;
    value = std::strtol(text, &end, 10);
    return end != text && *end == '\0' && value > 0;
  };
  long cells = 0, ranks = 0;
  if (argc != 3 || !whole_number(argv[1], cells) || !whole_number(argv[2], ranks)) {
    std::cerr << "usage: tfdem-gas-layout CELLS RANKS (whole numbers > 0): prints whole or split, the layout with "
                 "the shorter gas step by the rule measured in bench/README.md\n";
    return 2;
  }
  const tfdem::gas_layout::Layout layout = tfdem::gas_layout::recommended(double(cells), int(ranks));
  std::cout << tfdem::gas_layout::name(layout) << "\n";
  std::cerr << tfdem::gas_layout::advice(double(cells), int(ranks), layout) << "\n";
  return 0;
}
