// The marker of a joint gas/particle checkpoint, <case>/<time>/tfdem.checkpoint: the DEM clock
// and particle totals to resume from, how the gas was laid out over the ranks, and every file
// of the checkpoint (gas fields, the DEM restart file) with its digest, so a resumed run starts
// only from the bytes that were written and verified. Written last, so a time folder without
// it was never completed. Also lists the DEM script's output files and their sizes, for the
// resumed run to continue them from there. Text, one entry a line, "key value;" (the entries
// of earlier markers read the same; those list no files and are "legacy").
#ifndef TFDEM_CHECKPOINT_MANIFEST_H
#define TFDEM_CHECKPOINT_MANIFEST_H

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tfdem/file_digest.h"

namespace tfdem {

struct CheckpointManifest {
  double time = 0;                 // s
  bool dem_restart = false;        // a DEM restart file was written (none for an emptied bed)
  long long dem_step = 0;
  long long particles = 0;
  double particle_mass = 0;        // kg
  long long removed_particles = 0;  // left through outlets since the start
  double removed_mass = 0;         // kg
  std::string engine;              // the particle engine that wrote it ("" in earlier markers)
  std::string layout;              // "serial", "whole" or "split" (tfdemFoam's gas layouts)
  int ranks = 1;
  std::string write_format;        // the gas fields' writeFormat and writePrecision
  int write_precision = 0;
  struct File {
    std::string path;  // relative to the case
    FileDigest digest;
  };
  std::vector<File> files;
  std::vector<std::pair<std::string, std::uint64_t>> outputs;  // DEM output file, bytes

  // Written before markers listed their files: nothing to verify them by.
  bool legacy() const { return files.empty(); }
};

std::string format_manifest(const CheckpointManifest &manifest);

// Throws std::invalid_argument "file:line: what is wrong" for a damaged or foreign marker.
CheckpointManifest parse_manifest(const std::string &text, const std::string &file);

// What in a marker cannot be so, whatever the data (a hand edit, a damaged marker): each as
// "entry: value: why", for the marker of the time folder `folder_time` (s) whose DEM restart
// file, when it lists one, is `restart_path` (relative to the case).
std::vector<std::string> manifest_problems(const CheckpointManifest &manifest, double folder_time,
                                           const std::string &restart_path);

// Each listed file under `root` that is missing or differs from its digest, as
// "path: what differs" (sizes first: a file cut short is named without reading it whole).
std::vector<std::string> changed_files(const CheckpointManifest &manifest, const std::string &root);

}  // namespace tfdem

#endif
