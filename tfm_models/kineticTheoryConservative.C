#include "kineticTheoryConservative.H"

#include "addToRunTimeSelectionTable.H"
#include "fvc.H"
#include "phaseCompressibleTurbulenceModelFwd.H"
#include "phaseModel.H"

namespace Foam {

typedef RASModel<EddyDiffusivity<phaseCompressibleTurbulenceModel>> RASphaseCompressibleTurbulenceModel;

namespace RASModels {

defineTypeNameAndDebug(kineticTheoryConservative, 0);
addToRunTimeSelectionTable(RASphaseCompressibleTurbulenceModel, kineticTheoryConservative, dictionary);

kineticTheoryConservative::kineticTheoryConservative(const volScalarField &alpha, const volScalarField &rho,
                                                     const volVectorField &U, const surfaceScalarField &alphaRhoPhi,
                                                     const surfaceScalarField &phi, const phaseModel &transport,
                                                     const word &propertiesName, const word &type)
    : kineticTheoryModel(alpha, rho, U, alphaRhoPhi, phi, transport, propertiesName, type),
      phase_(transport),
      radial_(kineticTheoryModels::radialModel::New(coeffDict_)),
      pressure_(kineticTheoryModels::granularPressureModel::New(coeffDict_)),
      restitution_("e", dimless, coeffDict_),
      alphaMinFriction_("alphaMinFriction", dimless, coeffDict_),
      alphaMax_("alphaMax", dimless, coeffDict_) {}

tmp<fvVectorMatrix> kineticTheoryConservative::divDevRhoReff(volVectorField &U) const {
  const volScalarField &Theta = mesh_.lookupObject<volScalarField>(IOobject::groupName("Theta", phase_.name()));
  const volScalarField alpha(max(alpha_, scalar(0)));
  const volScalarField pressurePerTheta(pressure_->granularPressureCoeff(
      alpha, radial_->g0(alpha, alphaMinFriction_, alphaMax_), phase_.rho(), restitution_));
  tmp<fvVectorMatrix> equation(kineticTheoryModel::divDevRhoReff(U));
  // a term on the equation's left: the force -(P_s / Theta) grad(Theta) on its right
  equation.ref() += pressurePerTheta * fvc::grad(Theta);
  return equation;
}

}  // namespace RASModels
}  // namespace Foam
