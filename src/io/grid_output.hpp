// DMDA fields as HDF5 datasets plus the XDMF block that ParaView reads them through.
//
// Each field of a multi-dof DMDA vector becomes its own dataset /<group>/<name> in natural ordering:
// scalars [Nz][Ny][Nx], vectors (2 or 3 components) [Nz][Ny][Nx][3], padded with zeros to 3 so
// that ParaView shows them as vectors in 2-D too; in 2-D Nz = 1 ([1][Ny][Nx]), which is what
// ParaView's XDMF2 reader needs to place a 3DCoRectMesh in the x-y plane. The XDMF refers to each
// dataset directly: no HyperSlab (ParaView's XDMF2 reader prints HDF5 error traces for those, the
// Xdmf3 readers drop them). Works for node DMDAs (cells+1 points per direction) and cell-centred
// DMDAs (cells points, Center="Cell" on the node mesh). Checked by tests/check_paraview.py.
#pragma once
#include "petsc_compat.hpp"
#include <petscdmda.h>
#include <petscviewer.h>
#include <string>
#include <vector>

namespace burst {

struct GridField {
  std::string name;       // dataset and ParaView array name
  PetscInt    first_dof;  // first component in the DMDA vector's dof layout
  PetscInt    components; // 1 (scalar), 2 or 3 (vector, written padded to 3)
};

// Writes each field of the DMDA global vector `v` (dof = the DMDA's dof) as its own dataset
// /<group>/<name> into the open HDF5 viewer (collective). The dof-1 and dof-3 DMDAs used for the
// copies (same ownership as `da`, no ghosts, 3-D with one plane in 2-D) are created once per `da`
// and kept composed with it. The viewer
// must not have timestepping pushed (that would prepend a time axis; it is popped and restored).
PetscErrorCode WriteGridFields(PetscViewer h5, DM da, Vec v, const char group[], const std::vector<GridField> &fields);

// XDMF <Grid> element for one time level: a uniform grid on a 3DCoRectMesh of cells+1 points per
// direction (Dimensions and origin/spacing in z y x order; in 2-D one z plane at z = 0, or for
// cell-centred data one layer of cells of thickness dx around it) with one Attribute per field,
// pointing at h5_file:/<group>/<name>. cell_centred: the data have cells points per direction and
// are attached with Center="Cell"; otherwise cells+1 and Center="Node".
std::string XdmfGridBlock(const std::string &h5_file, const char group[], PetscInt dim, const PetscInt cells[3], const PetscReal lower[3], const PetscReal h[3], bool cell_centred, const std::vector<GridField> &fields, PetscReal time);

} // namespace burst
