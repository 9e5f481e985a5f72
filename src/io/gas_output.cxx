// Gas output: gas_NNNNNN.h5 with one dataset per cell field (/cells/pressure and, per material m,
// /cells/<m>_density (bulk, kg/m^3), <m>_velocity, <m>_temperature, <m>_volume_fraction) and the
// temporal collection gas.xmf, which ParaView opens beside particles.xmf (cell-centred data on the
// same grid; grid_output.hpp). Written under a temporary name and renamed, like the particles.
#include "../simulation.hpp"
#include "../ice/ice.hpp"
#include "grid_output.hpp"
#include <petscviewerhdf5.h>
#include <array>
#include <cstdio>
#include <fstream>

namespace burst {

namespace {
const char cell_group[] = "/cells";

std::vector<GridField> GasFields(const IceSolver &ice)
{
  std::vector<GridField> fields = {{"pressure", ice.CellOffset(icef::press), 1}};
  for (PetscInt m = 0; m < ice.nmat; ++m) {
    const std::string &n = ice.materials[m].name;
    fields.push_back({n + "_density", ice.Offset(m, icef::rho), 1});
    fields.push_back({n + "_velocity", ice.Offset(m, icef::vel), ice.dim});
    fields.push_back({n + "_temperature", ice.Offset(m, icef::temp), 1});
    fields.push_back({n + "_volume_fraction", ice.Offset(m, icef::theta), 1});
  }
  return fields;
}
} // namespace

PetscErrorCode WriteGasOutput(Simulation &sim)
{
  IceSolver  &ice = *sim.ice;
  PetscViewer viewer;
  char        name[64];
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(sim.output.ev_output, 0, 0, 0, 0));
  PetscCall(IceSyncGlobal(ice));
  std::snprintf(name, sizeof(name), "gas_%06d.h5", (int)sim.step);
  const std::string            path = sim.output.dir + "/" + name, tmp = path + ".tmp";
  const std::vector<GridField> fields = GasFields(ice);
  PetscCall(PetscViewerHDF5Open(sim.comm, tmp.c_str(), FILE_MODE_WRITE, &viewer));
  PetscCall(WriteGridFields(viewer, ice.da, ice.state, cell_group, fields));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, cell_group, "time", PETSC_REAL, &sim.time));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, cell_group, "step", PETSC_INT, &sim.step));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(AtomicRename(sim.comm, tmp, path));
  if (!sim.rank) {
    sim.output.gas_records.push_back({sim.step, sim.time});
    const std::string xmf = sim.output.dir + "/gas.xmf", xmf_tmp = xmf + ".tmp";
    {
      std::ofstream out(xmf_tmp);
      out << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n  <Grid Name=\"TimeSeries\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
      for (const GasOutputRecord &r : sim.output.gas_records) {
        std::snprintf(name, sizeof(name), "gas_%06d.h5", (int)r.step);
        out << XdmfGridBlock(name, cell_group, ice.dim, ice.cells, ice.lower, ice.h, true, fields, r.time);
      }
      out << "  </Grid>\n </Domain>\n</Xdmf>\n";
      PetscCheck(out.good(), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not write %s", xmf_tmp.c_str());
    }
    PetscCheck(std::rename(xmf_tmp.c_str(), xmf.c_str()) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not rename %s", xmf_tmp.c_str());
  }
  PetscCall(PetscLogEventEnd(sim.output.ev_output, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
