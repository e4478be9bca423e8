#include "physicsTerm.H"
#include "meltdemProperties.H"

namespace Foam
{
namespace meltdem
{
    defineTypeNameAndDebug(physicsTerm, 0);
    defineRunTimeSelectionTable(physicsTerm, properties);
}
}


std::map<std::string, Foam::meltdem::physicsTerm::termInfo>&
Foam::meltdem::physicsTerm::infoTable()
{
    static std::map<std::string, termInfo> table;
    return table;
}


namespace
{

void writeInfo(std::ostream& os, const Foam::meltdem::physicsTerm::termInfo& t)
{
    os << "{\"order\": " << t.order << ", \"what\": \"" << t.what << "\", \"needs\": [";
    for (std::size_t i = 0; i < t.needs.size(); ++i) os << (i ? ", " : "") << '"' << t.needs[i] << '"';
    os << "], \"entries\": {";
    bool first = true;
    for (const auto& d : t.entries)
    {
        os << (first ? "" : ", ") << '"' << d.first << "\": {";
        for (std::size_t i = 0; i < d.second.size(); ++i)
        {
            os << (i ? ", " : "") << '"' << d.second[i].key << "\": \"" << d.second[i].range << '"';
        }
        os << '}';
        first = false;
    }
    os << "}, \"acts\": [";
    for (std::size_t i = 0; i < t.acts.size(); ++i) os << (i ? ", " : "") << '"' << t.acts[i] << '"';
    os << "]}";
}

} // End anonymous namespace


void Foam::meltdem::physicsTerm::writeTable(std::ostream& os)
{
    // the solver's own switches (meltdemProperties.H) and what they read
    const std::vector<std::pair<std::string, termInfo>> core
    {
        {"flow", {"flow", 0, {}, {}, "the VOF flow (off: conduction only)", {"momentum"}}},
        {"energy", {"energy", 0, {}, {{"metal", {{"cp", "> 0"}, {"k", "> 0"}, {"L", ">= 0"},
                   {"Tsolidus", "> 0"}, {"Tliquidus", "> 0"}}}, {"gas", {{"cp", "> 0"}, {"k", "> 0"}}}},
                   "the energy equation with latent heat", {"energy"}}},
        {"particles", {"particles", 0, {}, {{"particles", {{"lammpsInput", "word"},
                      {"distribution", "centre neighbours overlap"}}}},
                      "LAMMPS particles in the same job (with flow off: one-way, the fields as given)",
                      {"energy", "momentum"}}}
    };
    os << "{\"core\": {";
    for (std::size_t i = 0; i < core.size(); ++i)
    {
        os << (i ? ", " : "") << '"' << core[i].first << "\": ";
        writeInfo(os, core[i].second);
    }
    os << "}, \"terms\": {";
    bool first = true;
    for (const auto& t : infoTable())
    {
        os << (first ? "" : ", ") << '"' << t.first << "\": ";
        writeInfo(os, t.second);
        first = false;
    }
    // the top level's own entries: with the terms' sub-dictionaries, all it may hold
    os << "}, \"topLevel\": [";
    const wordList& own = meltdemProperties::ownEntries();
    forAll(own, i) os << (i ? ", " : "") << '"' << own[i].c_str() << '"';
    os << "]}" << std::endl;
}


Foam::autoPtr<Foam::meltdem::physicsTerm> Foam::meltdem::physicsTerm::New
(
    const word& name,
    const fvMesh& mesh,
    const dictionary& properties
)
{
    auto cstrIter = propertiesConstructorTablePtr_->cfind(name);
    if (!cstrIter.found())
    {
        FatalIOErrorInFunction(properties)
            << "unknown physics term '" << name << "'; known terms: "
            << propertiesConstructorTablePtr_->sortedToc() << exit(FatalIOError);
    }
    return cstrIter()(mesh, properties);
}
