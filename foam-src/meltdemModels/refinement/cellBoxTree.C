#include "cellBoxTree.H"
#include "Random.H"

namespace Foam
{
namespace meltdem
{

defineTypeNameAndDebug(cellBoxTree, 0);


cellBoxTree::cellBoxTree(const fvMesh& mesh)
:
    MeshObject<fvMesh, UpdateableMeshObject, cellBoxTree>(mesh)
{}


const indexedOctree<treeDataCell>& cellBoxTree::tree() const
{
    if (!tree_.valid())
    {
        // as fvMesh::cellTree() builds it, but with each cell's box kept
        Random rnd(261782);
        treeBoundBox overall(mesh().points());
        overall = overall.extend(rnd, 1e-4);
        overall.min() -= point::uniform(ROOTVSMALL);
        overall.max() += point::uniform(ROOTVSMALL);
        tree_.reset
        (
            new indexedOctree<treeDataCell>
            (
                treeDataCell(true, mesh(), polyMesh::CELL_TETS),
                overall, 8, 10, 5.0
            )
        );
    }
    return *tree_;
}

} // End namespace meltdem
} // End namespace Foam
