// DMDA fields as one HDF5 dataset each, and their XDMF block (see grid_output.hpp).
#include "grid_output.hpp"
#include <petscviewerhdf5.h>
#include <cstdio>
#include <limits>
#include <sstream>

namespace burst {

namespace {
// "/name" for "name" or "/name"; the HDF5 group the fields go into.
std::string AbsoluteGroup(const char group[]) { return (group && group[0] == '/') ? std::string(group) : "/" + std::string(group ? group : ""); }

// The DMDA the fields of `da` are copied into before VecView: same points per process as `da`, dof
// `dof`, no ghosts, and always 3-D (one z plane in 2-D), so that every dataset has the rank ParaView's
// XDMF2 reader expects of a 3DCoRectMesh ([1][Ny][Nx] in 2-D; a 2DCoRectMesh would put the data in
// the y-z plane and its vectors fail to load). Created on first use and kept composed with `da`
// (freed with it), so the output does not rebuild it.
PetscErrorCode FieldDA(DM da, PetscInt dof, DM *fda)
{
  char        key[64];
  PetscObject obj = nullptr;
  PetscFunctionBeginUser;
  std::snprintf(key, sizeof(key), "burst_grid_output_dof%d", (int)dof);
  PetscCall(PetscObjectQuery((PetscObject)da, key, &obj));
  if (!obj) {
    PetscInt        dim, M, N, P, m, n, p;
    const PetscInt *l[3], one[1] = {1};
    DM              nda;
    PetscCall(DMDAGetInfo(da, &dim, &M, &N, &P, &m, &n, &p, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
    PetscCall(DMDAGetOwnershipRanges(da, &l[0], &l[1], &l[2]));
    if (dim < 3) P = p = 1, l[2] = one;
    if (dim < 2) N = n = 1, l[1] = one;
    PetscCall(DMDACreate3d(PetscObjectComm((PetscObject)da), DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_BOX, M, N, P, m, n, p, dof, 0, l[0], l[1], l[2], &nda));
    PetscCall(DMSetUp(nda));
    PetscCall(PetscObjectCompose((PetscObject)da, key, (PetscObject)nda));
    PetscCall(DMDestroy(&nda)); // da holds the reference now
    PetscCall(PetscObjectQuery((PetscObject)da, key, &obj));
  }
  *fda = (DM)obj;
  PetscFunctionReturn(PETSC_SUCCESS);
}
} // namespace

PetscErrorCode WriteGridFields(PetscViewer h5, DM da, Vec v, const char group[], const std::vector<GridField> &fields)
{
  PetscInt  dof, xm, ym, zm, n, nv;
  PetscBool timestepping;
  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(da, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, &dof, nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetCorners(da, nullptr, nullptr, nullptr, &xm, &ym, &zm));
  n = xm * ym * zm; // owned points (zm = ym = 1 below 3-D)
  PetscCall(VecGetLocalSize(v, &nv));
  PetscCheck(nv == n * dof, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "WriteGridFields: vector has %" PetscInt_FMT " local entries, the DMDA %" PetscInt_FMT " points x %" PetscInt_FMT " dof", nv, n, dof);
  for (const auto &f : fields)
    PetscCheck(f.components >= 1 && f.components <= 3 && f.first_dof >= 0 && f.first_dof + f.components <= dof, PetscObjectComm((PetscObject)da), PETSC_ERR_ARG_OUTOFRANGE,
               "WriteGridFields: field %s (dofs %" PetscInt_FMT "..%" PetscInt_FMT ") does not fit a DMDA of %" PetscInt_FMT " dof (1 to 3 components)", f.name.c_str(), f.first_dof, f.first_dof + f.components - 1, dof);

  PetscCall(PetscViewerHDF5IsTimestepping(h5, &timestepping));
  if (timestepping) PetscCall(PetscViewerHDF5PopTimestepping(h5));
  PetscCall(PetscViewerHDF5PushGroup(h5, AbsoluteGroup(group).c_str()));
  const PetscScalar *in;
  PetscCall(VecGetArrayRead(v, &in));
  for (const auto &f : fields) {
    const PetscInt out_dof = f.components == 1 ? 1 : 3;
    DM             fda     = nullptr;
    Vec            w;
    PetscScalar   *out;
    PetscCall(FieldDA(da, out_dof, &fda));
    PetscCall(DMGetGlobalVector(fda, &w));
    PetscCall(VecGetArray(w, &out));
    // Same ownership and local ordering in both vectors: point p's dofs are contiguous.
    for (PetscInt p = 0; p < n; ++p)
      for (PetscInt c = 0; c < out_dof; ++c) out[p * out_dof + c] = c < f.components ? in[p * dof + f.first_dof + c] : 0;
    PetscCall(VecRestoreArray(w, &out));
    PetscCall(PetscObjectSetName((PetscObject)w, f.name.c_str()));
    PetscCall(VecView(w, h5)); // a DMDA global vector: natural ordering, [Nz][Ny][Nx](+[3]), Nz = 1 in 2-D
    PetscCall(DMRestoreGlobalVector(fda, &w));
  }
  PetscCall(VecRestoreArrayRead(v, &in));
  PetscCall(PetscViewerHDF5PopGroup(h5));
  if (timestepping) PetscCall(PetscViewerHDF5PushTimestepping(h5));
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string XdmfGridBlock(const std::string &h5_file, const char group[], PetscInt dim, const PetscInt cells[3], const PetscReal lower[3], const PetscReal h[3], bool cell_centred, const std::vector<GridField> &fields, PetscReal time)
{
  const std::string  g         = AbsoluteGroup(group);
  const int          precision = (int)sizeof(PetscReal);
  std::ostringstream mesh, data, origin, spacing, s;
  s.precision(std::numeric_limits<PetscReal>::max_digits10);
  origin.precision(std::numeric_limits<PetscReal>::max_digits10);
  spacing.precision(std::numeric_limits<PetscReal>::max_digits10);
  // XDMF lists the slowest index first: z y x. A 2-D grid is one z plane of a 3DCoRectMesh, so that
  // ParaView puts it in the x-y plane (a 2DCoRectMesh lands in the y-z plane, and the XDMF2 reader
  // fails on its vectors); the datasets are [1][Ny][Nx] (WriteGridFields). Cell-centred 2-D data sit
  // on one layer of cells, z in [-dz/2, dz/2] with dz = dx (the XDMF2 reader cannot attach cell data
  // to a single plane of points).
  for (PetscInt d = 2; d >= 0; --d) {
    const char *sep = d ? " " : "";
    const bool  in  = d < dim;
    mesh << (in ? cells[d] + 1 : (cell_centred ? 2 : 1)) << sep;
    data << (in ? (cell_centred ? cells[d] : cells[d] + 1) : 1) << sep;
    origin << (in ? lower[d] : (cell_centred ? -0.5 * h[0] : 0)) << sep;
    spacing << (in ? h[d] : h[0]) << sep;
  }
  s << "    <Grid Name=\"" << g.substr(1) << "\" GridType=\"Uniform\">\n      <Time Value=\"" << time << "\"/>\n";
  s << "      <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << mesh.str() << "\"/>\n";
  s << "      <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n";
  s << "        <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"" << precision << "\" Format=\"XML\">" << origin.str() << "</DataItem>\n";
  s << "        <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"" << precision << "\" Format=\"XML\">" << spacing.str() << "</DataItem>\n      </Geometry>\n";
  for (const auto &f : fields) {
    const bool scalar = f.components == 1;
    s << "      <Attribute Name=\"" << f.name << "\" AttributeType=\"" << (scalar ? "Scalar" : "Vector") << "\" Center=\"" << (cell_centred ? "Cell" : "Node") << "\">\n";
    s << "        <DataItem Dimensions=\"" << data.str() << (scalar ? "" : " 3") << "\" NumberType=\"Float\" Precision=\"" << precision << "\" Format=\"HDF\">" << h5_file << ":" << g << "/" << f.name << "</DataItem>\n      </Attribute>\n";
  }
  s << "    </Grid>\n";
  return s.str();
}

} // namespace burst
