// LIGGGHTS' screen output as the coupler gives it: a C stream that writes to the DEM log
// file (rank 0) and copies every ERROR line, and the first warnings, to this rank's stderr
// with the rank and the path of the full log. LIGGGHTS stops on an error with exit() or
// MPI_Abort() right after printing it, so the copy is made as the line is written. A line
// repeated kRepeatsTolerated times in a row (LIGGGHTS looping on a damaged input, as its
// restart reader does on a file cut short) stops the run instead of filling the disk.
#ifndef TFDEM_DEM_CONSOLE_H
#define TFDEM_DEM_CONSOLE_H

#include <cstdio>
#include <string>

namespace tfdem {

class DemConsole {
 public:
  // Output to `log_path` when `keep_log` (rank 0; appended when `append`, else written
  // anew), else only the copied lines.
  DemConsole(const std::string &log_path, bool keep_log, int rank, bool append);
  ~DemConsole();
  DemConsole(const DemConsole &) = delete;
  DemConsole &operator=(const DemConsole &) = delete;

  // The stream to hand LIGGGHTS as its screen (line-buffered).
  std::FILE *stream() const { return stream_; }
  // Close the stream now (LIGGGHTS closes it itself before exit() on an error).
  void close();

  // Called by the stream: one complete line of output (without its newline).
  void line(const std::string &text);

  static constexpr int kWarningsCopied = 10;
  static constexpr int kRepeatsTolerated = 1000;

 private:
  std::string log_path_;
  std::FILE *log_ = nullptr;
  std::FILE *stream_ = nullptr;
  int rank_ = 0;
  int warnings_ = 0;
  std::string last_line_;
  int repeats_ = 0;
  bool closed_ = false;
};

}  // namespace tfdem

#endif
