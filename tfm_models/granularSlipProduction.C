#include "granularSlipProduction.H"

#include "IOdictionary.H"
#include "addToRunTimeSelectionTable.H"
#include "dragModel.H"
#include "fvm.H"
#include "mathematicalConstants.H"
#include "phaseModel.H"
#include "radialModel.H"
#include "twoPhaseSystem.H"

namespace Foam {
namespace fv {

defineTypeNameAndDebug(granularSlipProduction, 0);
addToRunTimeSelectionTable(option, granularSlipProduction, dictionary);

const Enum<granularSlipProduction::production> granularSlipProduction::productionNames{
    {production::none, "none"}, {production::KochSangani, "KochSangani"}};

granularSlipProduction::granularSlipProduction(const word &name, const word &modelType, const dictionary &dict,
                                               const fvMesh &mesh)
    : option(name, modelType, dict, mesh) {
  read(dict);
}

bool granularSlipProduction::read(const dictionary &dict) {
  if (!option::read(dict)) {
    return false;
  }
  phaseName_ = coeffs_.get<word>("phase");
  production_ = productionNames.get("production", coeffs_);
  fieldNames_ = wordList(1, IOobject::groupName("Theta", phaseName_));
  applied_ = List<bool>(1, false);
  return true;
}

const dictionary &granularSlipProduction::kineticCoefficients() const {
  const auto &properties = mesh_.lookupObject<IOdictionary>(IOobject::groupName("turbulenceProperties", phaseName_));
  const dictionary &ras = properties.subDict("RAS");
  return ras.subDict(ras.get<word>("RASModel") + "Coeffs");
}

void granularSlipProduction::addSup(const volScalarField &alpha, const volScalarField &rho, fvMatrix<scalar> &eqn,
                                    const label) {
  // alpha and rho are the ones kineticTheoryModel::correct passes: max(alpha_s, 0) and rho_s
  // phaseModel is the phase's alpha field (refCast cannot name its type: two typeNames)
  const auto &phase =
      dynamic_cast<const phaseModel &>(mesh_.lookupObject<volScalarField>(IOobject::groupName("alpha", phaseName_)));
  const twoPhaseSystem &fluid = phase.fluid();
  const phaseModel &gas = fluid.otherPhase(phase);
  const volScalarField &theta = eqn.psi();
  const dictionary &kinetic = kineticCoefficients();
  const dimensionedScalar residualAlpha("residualAlpha", dimless, kinetic);
  const dimensionedScalar thetaSmall("ThetaSmall", theta.dimensions(), 1.0e-6);  // kineticTheoryModel's
  const scalar sqrtPi = sqrt(constant::mathematical::pi);

  const volScalarField beta(fluid.lookupSubModel<dragModel>(phase, gas).K());
  const tmp<volScalarField> d(phase.d());
  const volScalarField slipSquared(magSqr(phase.U() - gas.U()));
  const volScalarField sqrtTheta(sqrt(theta));

  // v1912's J2, taken away in the form it is added: Sp(J2 / (Theta + ThetaSmall), Theta)
  const volScalarField gidaspow(0.25 * sqr(beta) * d() * slipSquared /
                                (max(alpha, residualAlpha) * rho * sqrtPi * (sqrtTheta + sqrt(thetaSmall))));
  eqn += fvm::Sp(-gidaspow / (theta + thetaSmall), theta);

  if (production_ == production::KochSangani) {
    const auto radial = kineticTheoryModels::radialModel::New(kinetic);
    const volScalarField g0(radial->g0(alpha, dimensionedScalar("alphaMinFriction", dimless, kinetic),
                                       dimensionedScalar("alphaMax", dimless, kinetic)));
    const volScalarField kochSangani(81.0 * alpha * sqr(gas.mu()) * slipSquared /
                                     (g0 * pow3(d()) * rho * sqrtPi * (sqrtTheta + sqrt(thetaSmall))));
    eqn += kochSangani;
  }
}

}  // namespace fv
}  // namespace Foam
