#include "dem_console.h"

#include <mpi.h>

#include <cstring>

namespace tfdem {
namespace {

// Cookie of the stream: the console and the unfinished last line.
struct Cookie {
  DemConsole *console;
  std::string pending;
};

ssize_t write_cookie(void *cookie, const char *buffer, size_t size) {
  auto *c = static_cast<Cookie *>(cookie);
  c->pending.append(buffer, size);
  for (std::size_t end; (end = c->pending.find('\n')) != std::string::npos;) {
    c->console->line(c->pending.substr(0, end));
    c->pending.erase(0, end + 1);
  }
  return static_cast<ssize_t>(size);
}

int close_cookie(void *cookie) {
  auto *c = static_cast<Cookie *>(cookie);
  if (!c->pending.empty()) c->console->line(c->pending);
  c->console->close();
  delete c;
  return 0;
}

bool starts_with(const std::string &text, const char *prefix) {
  return text.compare(0, std::strlen(prefix), prefix) == 0;
}

}  // namespace

DemConsole::DemConsole(const std::string &log_path, bool keep_log, int rank, bool append)
    : log_path_(log_path), rank_(rank) {
  if (keep_log) log_ = std::fopen(log_path.c_str(), append ? "a" : "w");
  cookie_io_functions_t functions{nullptr, write_cookie, nullptr, close_cookie};
  stream_ = fopencookie(new Cookie{this, ""}, "w", functions);
  if (stream_) std::setvbuf(stream_, nullptr, _IOLBF, 0);
}

DemConsole::~DemConsole() {
  if (stream_ && !closed_) std::fclose(stream_);  // close_cookie() closes the log
}

void DemConsole::close() {
  if (closed_) return;
  closed_ = true;
  if (log_) std::fclose(log_);
  log_ = nullptr;
}

void DemConsole::line(const std::string &text) {
  repeats_ = text == last_line_ ? repeats_ + 1 : 0;
  last_line_ = text;
  if (repeats_ == kRepeatsTolerated) {
    std::fprintf(stderr,
                 "[DEM rank %d] LIGGGHTS printed this line %d times in a row and is stopped (it loops, e.g. on a "
                 "damaged file it reads): %s\n[DEM rank %d] full LIGGGHTS output: %s\n",
                 rank_, kRepeatsTolerated, text.c_str(), rank_, log_path_.c_str());
    if (log_) std::fflush(log_);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  if (repeats_ > 10) return;  // the log keeps the first repeats
  if (log_) std::fprintf(log_, "%s\n", text.c_str());
  const bool error = starts_with(text, "ERROR");
  const bool warning = starts_with(text, "WARNING") && warnings_ < kWarningsCopied;
  if (!error && !warning) return;
  std::fprintf(stderr, "[DEM rank %d] LIGGGHTS %s\n", rank_, text.c_str());
  if (warning && ++warnings_ == kWarningsCopied)
    std::fprintf(stderr, "[DEM rank %d] further LIGGGHTS warnings only in %s\n", rank_, log_path_.c_str());
  if (error)
    std::fprintf(stderr, "[DEM rank %d] the DEM stopped; full LIGGGHTS output: %s\n", rank_, log_path_.c_str());
  std::fflush(stderr);
}

}  // namespace tfdem
