#include "tfdemStop.H"

#include <mpi.h>

#include <csignal>
#include <cstring>

namespace
{

volatile std::sig_atomic_t received = 0;
int agreedSignal = 0;

// The first signal asks for the checkpoint; a second one (a run stuck before its next gas
// step, or an impatient user) ends the process at once, as the signal would without us
void handler(int signal)
{
    if (received == 0)
    {
        received = signal;
        return;
    }
    ::signal(signal, SIG_DFL);
    ::raise(signal);
}

} // End anonymous namespace


void Foam::tfdemStop::install()
{
    for (const int signal : {SIGTERM, SIGINT, SIGUSR1})
    {
        struct sigaction action;
        std::memset(&action, 0, sizeof action);
        action.sa_handler = handler;
        sigemptyset(&action.sa_mask);
        ::sigaction(signal, &action, nullptr);
    }
}


bool Foam::tfdemStop::agreed()
{
    int flag = received;
    int started = 0;
    MPI_Initialized(&started);
    if (started)
    {
        MPI_Allreduce(MPI_IN_PLACE, &flag, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    }
    if (flag != 0 && agreedSignal == 0) agreedSignal = flag;
    return agreedSignal != 0;
}


int Foam::tfdemStop::signal()
{
    return agreedSignal;
}


const char* Foam::tfdemStop::signalName()
{
    switch (agreedSignal)
    {
        case SIGTERM: return "SIGTERM";
        case SIGINT: return "SIGINT";
        case SIGUSR1: return "SIGUSR1";
        default: return "a signal";
    }
}
