#include "tfdemFailure.H"

#include <csignal>
#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace
{

volatile std::sig_atomic_t phase = 0;
volatile double simulatedTime = 0;
char lastCheckpoint[64] = "";
struct sigaction previous[3];
const int signals[3] = {SIGFPE, SIGSEGV, SIGBUS};

// Per phase: what it is, and what makes it fail
const char* const phases[][2] =
{
    {"start-up", "a setting the checks did not catch"},
    {
        "the DEM interval (LIGGGHTS)",
        "a contact that blew up (DEM step too long for the stiffness: see the contact-time"
        " lines at start), particles placed at one point, or a fluid force that is not finite"
    },
    {
        "the coupling step (void fraction, drag)",
        "a gas velocity or pressure gradient that is no longer finite (the gas diverged the"
        " step before) or a particle state that is not finite"
    },
    {
        "the gas solve (PIMPLE)",
        "the gas diverged: a gas step too long for the inflow (see the Courant lines at each"
        " write), a void fraction too small for the drag law, or solver tolerances too loose"
    },
    {"writing the fields or the checkpoint", "a value that is no longer finite"}
};

void handler(int signal)
{
    int which = 0;
    while (which < 3 && signals[which] != signal) ++which;
    const int p = (phase >= 0 && phase < 5) ? int(phase) : 0;
    char text[1024];
    const int n = std::snprintf
    (
        text, sizeof text,
        "\nTFDEM: %s in %s at t = %.9g s. Likely: %s. %s%s%s\n",
        signal == SIGFPE
      ? "floating-point exception (a NaN, a division by zero or an overflow)"
      : "memory fault (a bug: please report it with the case)",
        phases[p][0], double(simulatedTime), phases[p][1],
        lastCheckpoint[0] ? "The last good checkpoint is t = " : "No checkpoint was written",
        lastCheckpoint, lastCheckpoint[0] ? " s." : "."
    );
    if (n > 0) (void)!::write(STDERR_FILENO, text, std::strlen(text));
    if (which < 3)
    {
        ::sigaction(signal, &previous[which], nullptr);
    }
    else
    {
        ::signal(signal, SIG_DFL);
    }
    ::raise(signal);
}

} // End anonymous namespace


void Foam::tfdemFailure::install()
{
    for (int k = 0; k < 3; ++k)
    {
        struct sigaction action;
        std::memset(&action, 0, sizeof action);
        action.sa_handler = handler;
        sigemptyset(&action.sa_mask);
        ::sigaction(signals[k], &action, &previous[k]);
    }
}


void Foam::tfdemFailure::enter(Phase p, double t)
{
    simulatedTime = t;
    phase = std::sig_atomic_t(p);
}


void Foam::tfdemFailure::checkpointWritten(const std::string& timeName)
{
    std::snprintf(lastCheckpoint, sizeof lastCheckpoint, "%s", timeName.c_str());
}
