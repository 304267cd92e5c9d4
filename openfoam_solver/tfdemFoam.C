/*---------------------------------------------------------------------------*\
Application
    tfdemFoam

Description
    Gas-phase solver of TFDEM: volume-averaged incompressible gas equations of
    the hybrid two-fluid/DEM method (seed 001 eq. 7-9; seed 000 eq. 1 and 3):

        d(eps)/dt + div(eps U) = 0
        d(eps U)/dt + div(eps U U) - div(eps nu grad U)
            = -eps grad(p)/rho + eps g - K (U - Us)/rho

    with gas volume fraction eps, pressure p in Pa, the semi-implicit drag
    coefficient K (kg/m^3/s) and the particle-mean velocity Us handed over by
    the coupling. Without particles (eps = 1, K = 0) it is the incompressible
    PIMPLE solver with pressure in Pa. Explicit forces (gravity, explicit drag)
    enter through face fluxes as in DPMFoam so the pressure equation stays
    consistent with them.
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "pimpleControl.H"
#include "fvOptions.H"
#include "tfdemCase.H"
#include "tfdemCoupling.H"
#include "tfdemFailure.H"
#include "tfdemRanks.H"
#include "tfdemStartupChecks.H"
#include "tfdemStop.H"
#include "tfdemTime.H"

#include <chrono>
#include <cstdlib>

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Volume-averaged gas solver of the TFDEM hybrid two-fluid/DEM method."
    );

    argList::addOption
    (
        "recordForces",
        "file",
        "Write every coupling step's particle fluid forces to file.<rank> (binary), for"
        " the DEM-only replay of bench/bench_bubbling_bed.py"
    );

    #include "postProcess.H"

    TfdemCase::checkArguments(argc, argv);
    TfdemRanks::start(argc, argv);

    #include "addCheckCaseOptions.H"
    #include "setRootCaseLists.H"
    tfdemFailure::install();
    tfdemStop::install();
    TfdemCase::checkControlDict(args);
    const fileName forceRecordFile
    (
        TfdemCase::absolute(args.getOrDefault<fileName>("recordForces", fileName()))
    );

    Info<< "Create time\n" << endl;
    TfdemTime runTime(Time::controlDictName, args);
    TfdemCase::messagePrecision(10);
    TfdemRanks::checkTime(runTime);
    const TfdemCase tfdemCase(runTime);
    // A coupled run's start time verified (or refused) before any field of it is read
    autoPtr<TfdemCheckpoint> checkpoint
    (
        TfdemCase::coupled(runTime) ? new TfdemCheckpoint(runTime) : nullptr
    );
    #include "createMesh.H"
    TfdemRanks::adviseLayout(returnReduce(mesh.nCells(), sumOp<label>()));
    #include "createControl.H"
    #include "createTimeControls.H"
    #include "createFields.H"
    #include "createFvOptions.H"
    #include "createCoupling.H"
    #include "initContinuityErrs.H"

    Info<< "\nStarting time loop\n" << endl;

    while (runTime.run())
    {
        #include "readTimeControls.H"
        #include "CourantNo.H"
        #include "setDeltaT.H"

        // Asked to stop: this step is written (the joint checkpoint) and is the last
        if (tfdemStop::agreed())
        {
            runTime.stopAt(Time::stopAtControls::saWriteNow);
        }

        ++runTime;

        Info<< "Time = " << runTime.timeName() << nl << endl;

        particlePhase->evolve();

        const auto gasStart = std::chrono::steady_clock::now();
        tfdemFailure::enter(tfdemFailure::Phase::gas, runTime.value());
        while (pimple.loop())
        {
            #include "UEqn.H"

            while (pimple.correct())
            {
                #include "pEqn.H"
            }
        }
        particlePhase->gasSolved
        (
            std::chrono::duration<double>(std::chrono::steady_clock::now() - gasStart).count()
        );

        if (runTime.writeTime())
        {
            tfdemFailure::enter(tfdemFailure::Phase::writing, runTime.value());
            particlePhase->write();
        }

        particlePhase->progress(CoNum);

        runTime.printExecutionTime(Info);
    }

    particlePhase->report();
    particlePhase.clear();

    if (tfdemStop::signal())
    {
        Info<< "TFDEM stop: " << tfdemStop::signalName() << " received; stopped at t = "
            << runTime.timeName() << " s, its fields and checkpoint written. Resume with"
            << " startFrom latestTime" << endl;
        TfdemRanks::finish();
        std::exit(tfdemStop::exitCode);  // not return: ~argList would exit 0 under mpirun
    }

    Info<< "End\n" << endl;

    TfdemRanks::finish();

    return 0;
}
