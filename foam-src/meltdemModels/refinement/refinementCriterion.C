#include "refinementCriterion.H"
#include "meltdemProperties.H"

namespace Foam
{
namespace meltdem
{

defineTypeNameAndDebug(refinementCriterion, 0);
defineRunTimeSelectionTable(refinementCriterion, dictionary);


refinementCriterion::refinementCriterion
(
    const word& name, const dictionary& dict, const fvMesh& mesh, const label maxLevel
)
:
    name_(name),
    dict_(dict),
    mesh_(mesh),
    level_(dict.getOrDefault<label>("level", maxLevel))
{
    if (level_ < 1 || level_ > maxLevel)
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "': level " << level_
            << " must be between 1 and maxLevel " << maxLevel << exit(FatalIOError);
    }
}


autoPtr<refinementCriterion> refinementCriterion::New
(
    const word& name, const dictionary& dict, const fvMesh& mesh, const label maxLevel
)
{
    const word type(dict.getOrDefault<word>("type", name));
    auto cstrIter = dictionaryConstructorTablePtr_->cfind(type);
    if (!cstrIter.found())
    {
        FatalIOErrorInFunction(dict)
            << "unknown refinement criterion type '" << type << "' for '" << name
            << "'; known types: " << dictionaryConstructorTablePtr_->sortedToc()
            << exit(FatalIOError);
    }
    autoPtr<refinementCriterion> criterion(cstrIter()(name, dict, mesh, maxLevel));
    wordList known(criterion->entries());
    known.append(word("type"));
    known.append(word("level"));
    meltdemProperties::checkEntries(dict, known, "refinement criterion " + name + ", type " + type);
    return criterion;
}


scalar refinementCriterion::nonNegative(const word& key, const scalar deflt) const
{
    const scalar v = dict_.getOrDefault<scalar>(key, deflt);
    if (!(v >= 0))
    {
        FatalIOErrorInFunction(dict_)
            << "refinement criterion '" << name_ << "': entry '" << key << "' = " << v
            << " must be non-negative" << exit(FatalIOError);
    }
    return v;
}


const volScalarField& refinementCriterion::namedField(const word& key, const word& deflt) const
{
    const word fieldName(deflt.empty() ? dict_.get<word>(key) : dict_.getOrDefault<word>(key, deflt));
    if (!mesh_.foundObject<volScalarField>(fieldName))
    {
        FatalIOErrorInFunction(dict_)
            << "refinement criterion '" << name_ << "': entry '" << key << "' names field '"
            << fieldName << "', which this run does not have; scalar fields it has: "
            << mesh_.sortedNames<volScalarField>() << exit(FatalIOError);
    }
    return mesh_.lookupObject<volScalarField>(fieldName);
}

} // End namespace meltdem
} // End namespace Foam
