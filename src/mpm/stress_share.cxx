// Sharing the stress update between ranks.
//
// DMSwarm keeps a particle on the rank that owns its cell, so where the solid fills only part of the
// grid one rank does the constitutive work of all its points while the others wait for it at the
// next ghost exchange (the exploding cylinders on two ranks: every particle on rank 0). The update is
// pointwise and the models see arrays, not the swarm (models/material.hpp), so a crowded rank sends
// the inputs of a share of its points to a rank with fewer; that rank runs the same models on them
// and sends the results back while the sender updates the points it kept. Each point gets the same
// arithmetic on whichever rank runs it, so a run is bit for bit the run without sharing.
//
// Every rank draws the same plan (one MPI_Allgather) from each rank's work: its particle count times
// its measured update time per particle, since the points of one rank may be far cheaper than
// another's (a rigid anvil's against a copper rod's). The ranks above the level that evens the work
// out send to those below, in rank order (the plan: stress_share_plan.cxx). A sender sends
// points spread evenly over its local array, so that each share holds its materials in the
// proportions of the whole. The message of n points is one buffer of field blocks, each 8-byte
// aligned: first the fields a model writes (stress, temperature, wave speed, internal energy, the
// state fields), then those it only reads (material, L, F, mass, volume, id, seeding size). The
// receiver points a MaterialPointFields into the buffer and returns its first part, the outputs.
#include "mpm/mpm.hpp"
#include "mpm/material_state.hpp"
#include "mpm/stress_share_plan.hpp"
#include "util.hpp"
#include <algorithm>
#include <cstring>

namespace burst {

namespace {

constexpr int      kTagHeader = 19998, kTagInputs = 19999, kTagResults = 20000; // results: kTagResults + the message's index in its transfer
constexpr PetscInt kChunkPoints = 1024;                                         // points per message: the receiver works on one while the next arrives

// One field of a message: its element size and block size, and where the sender's swarm holds it.
struct Block {
  size_t   elem;
  PetscInt bs;
  void    *base;
};

// The state fields (indices into f.state) that material `id` may touch: its own and those of every
// material that shares one of its fields (the materials of one model share their fields, and a
// model may look at whether a field of the model is registered at all).
std::vector<int> MaterialStateFields(const MpmSolver &mpm, const MaterialState &state, PetscInt id)
{
  std::vector<char> group(mpm.materials.size(), 0);
  group[id] = 1;
  for (bool grew = true; grew;) {
    grew = false;
    for (size_t a = 0; a < mpm.materials.size(); ++a)
      for (size_t b = 0; b < mpm.materials.size(); ++b) {
        if (!group[a] || group[b]) continue;
        for (const StateField &fa : mpm.materials[a]->StateFields())
          for (const StateField &fb : mpm.materials[b]->StateFields())
            if (!std::strcmp(fa.name, fb.name)) group[b] = 1, grew = true;
      }
  }
  std::vector<int> fields;
  for (int k = 0; k < state.Count(); ++k) {
    const char *name   = state.Field(k).name;
    bool        wanted = false;
    for (size_t a = 0; a < mpm.materials.size() && !wanted; ++a)
      if (group[a])
        for (const StateField &fa : mpm.materials[a]->StateFields()) wanted = wanted || !std::strcmp(fa.name, name);
    if (wanted) fields.push_back(k);
  }
  return fields;
}

// The blocks of a message of material points in message order: first the num_outputs that a model
// writes (stress, temperature, wave speed, internal energy, the material's state fields), then what
// it only reads (material, L, F, mass, volume, id, seeding size).
void ListBlocks(const MaterialPointFields &f, const std::vector<int> &state_fields, std::vector<Block> &blocks, size_t *num_outputs)
{
  blocks.clear();
  blocks.push_back({sizeof(PetscReal), 9, f.stress});
  blocks.push_back({sizeof(PetscReal), 1, f.temperature});
  blocks.push_back({sizeof(PetscReal), 1, f.wave_speed});
  blocks.push_back({sizeof(PetscReal), 1, f.internal_energy});
  for (int k : state_fields) {
    const MaterialState::FieldView field = f.state->Field(k);
    blocks.push_back({field.is_int ? sizeof(PetscInt) : sizeof(PetscReal), field.bs, field.array});
  }
  *num_outputs = blocks.size();
  blocks.push_back({sizeof(PetscInt), 1, const_cast<PetscInt *>(f.material)});
  blocks.push_back({sizeof(PetscReal), 9, const_cast<PetscReal *>(f.L)});
  blocks.push_back({sizeof(PetscReal), 9, const_cast<PetscReal *>(f.F)});
  blocks.push_back({sizeof(PetscReal), 1, const_cast<PetscReal *>(f.mass)});
  blocks.push_back({sizeof(PetscReal), 1, const_cast<PetscReal *>(f.volume)});
  blocks.push_back({sizeof(PetscInt64), 1, const_cast<PetscInt64 *>(f.id)});
  if (f.half_width0) blocks.push_back({sizeof(PetscReal), f.dim, const_cast<PetscReal *>(f.half_width0)});
  else blocks.push_back({sizeof(PetscReal), 1, const_cast<PetscReal *>(f.volume0)});
}

// Byte offsets of the blocks for n points (offsets.back() is the message size).
void Offsets(const std::vector<Block> &blocks, PetscInt n, std::vector<size_t> &offsets)
{
  offsets.assign(blocks.size() + 1, 0);
  for (size_t b = 0; b < blocks.size(); ++b) {
    const size_t end = offsets[b] + (size_t)n * blocks[b].bs * blocks[b].elem;
    offsets[b + 1]   = (end + 7) / 8 * 8;
  }
}

// Copies the points idx[0..n) of a block between the swarm (base) and the message (packed), a run of
// consecutive points at a time.
template <class T>
void Move(T *base, PetscInt bs, const PetscInt *idx, PetscInt n, T *packed, bool to_message)
{
  for (PetscInt j = 0; j < n;) {
    PetscInt run = 1;
    while (j + run < n && idx[j + run] == idx[j] + run) ++run;
    T *swarm = base + (size_t)idx[j] * bs, *message = packed + (size_t)j * bs;
    if (to_message) std::memcpy(message, swarm, sizeof(T) * run * bs);
    else std::memcpy(swarm, message, sizeof(T) * run * bs);
    j += run;
  }
}
void MoveBlock(const Block &block, const PetscInt *idx, PetscInt n, char *packed, bool to_message)
{
  if (block.elem == 8) Move(static_cast<uint64_t *>(block.base), block.bs, idx, n, reinterpret_cast<uint64_t *>(packed), to_message);
  else Move(static_cast<uint32_t *>(block.base), block.bs, idx, n, reinterpret_cast<uint32_t *>(packed), to_message);
}

// A MaterialPointFields over a received message of n points of one material, shaped like the
// receiver's own `like` (every rank registers the same fields).
PetscErrorCode ViewMessage(const MaterialPointFields &like, const std::vector<int> &state_fields, PetscInt n, char *buffer, const std::vector<size_t> &offsets, MaterialPointFields &g, MaterialState &state)
{
  size_t b  = 0;
  auto   at = [&](size_t k) { return buffer + offsets[k]; };
  PetscFunctionBeginUser;
  g.n               = n;
  g.dim             = like.dim;
  g.time            = like.time;
  g.cell_size       = like.cell_size;
  g.stress          = reinterpret_cast<PetscReal *>(at(b++));
  g.temperature     = reinterpret_cast<PetscReal *>(at(b++));
  g.wave_speed      = reinterpret_cast<PetscReal *>(at(b++));
  g.internal_energy = reinterpret_cast<PetscReal *>(at(b++));
  for (int k : state_fields) {
    const MaterialState::FieldView field = like.state->Field(k);
    PetscCall(state.Add(field.name, field.bs, field.is_int, at(b++)));
  }
  g.state    = &state;
  g.material = reinterpret_cast<const PetscInt *>(at(b++));
  g.L        = reinterpret_cast<const PetscReal *>(at(b++));
  g.F        = reinterpret_cast<const PetscReal *>(at(b++));
  g.mass     = reinterpret_cast<const PetscReal *>(at(b++));
  g.volume   = reinterpret_cast<const PetscReal *>(at(b++));
  g.id       = reinterpret_cast<const PetscInt64 *>(at(b++));
  if (like.half_width0) g.half_width0 = reinterpret_cast<const PetscReal *>(at(b++));
  else g.volume0 = reinterpret_cast<const PetscReal *>(at(b++));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode UpdateAllMaterials(MpmSolver &mpm, const MaterialPointFields &f)
{
  PetscFunctionBeginUser;
  for (PetscInt id = 0; id < (PetscInt)mpm.materials.size(); ++id) PetscCall(mpm.materials[id]->UpdateStress(f, id, mpm.dt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The plan's measured figures follow the run's drift but not one noisy step: each step's sample moves
// them by 0.3 of the difference.
void Smooth(PetscReal &figure, PetscReal sample) { figure = 0.7 * figure + 0.3 * sample; }

// A rank's time per point of its own update, smoothed over steps (the first measurement taken whole).
void MeasureCost(StressShare &share, PetscLogDouble seconds, PetscInt points)
{
  if (points <= 0 || !(seconds > 0)) return;
  if (share.seconds_per_point > 0) Smooth(share.seconds_per_point, seconds / points);
  else share.seconds_per_point = seconds / points;
}

} // namespace

PetscErrorCode StressShareSetUp(MpmSolver &mpm)
{
  StressShare &share = mpm.stress_share;
  PetscFunctionBeginUser;
  PetscOptionsBegin(mpm.comm, "", "Sharing the stress update between ranks", "Swarm");
  PetscCall(PetscOptionsBool("-mpm_stress_share", "Ranks with more stress-update work than their share send the update of a part of their particles to ranks with less (bit for bit the same run)", "", share.enabled, &share.enabled, nullptr));
  const char *const balances[] = {"time", "count"};
  PetscInt          balance    = (PetscInt)share.balance;
  PetscCall(PetscOptionsEList("-mpm_stress_share_balance", "What the plan evens out: time (count times measured time per particle) or count (particles: a plan from the decomposition alone)", "", balances, 2, balances[balance], &balance, nullptr));
  share.balance = (StressShare::Balance)balance;
  PetscCall(PetscOptionsReal("-mpm_stress_share_threshold", "Share only when the most loaded rank's work exceeds the mean by this fraction (-), >= 0", "", share.threshold, &share.threshold, nullptr));
  PetscCall(PetscOptionsInt("-mpm_stress_share_min", "Share only when the most loaded rank's work exceeds the mean by at least that of this many of its particles (particles), >= 0", "", share.min_points, &share.min_points, nullptr));
  PetscOptionsEnd();
  PetscCall(CheckRange(mpm.comm, "-mpm_stress_share_threshold", share.threshold, 0, PETSC_MAX_REAL, PETSC_FALSE));
  PetscCheck(share.min_points >= 0, mpm.comm, PETSC_ERR_USER_INPUT, "Option -mpm_stress_share_min = %" PetscInt_FMT " is out of range: it must be >= 0", share.min_points);
  if (!share.ev_share) PetscCall(PetscLogEventRegister("MPM_StressShare", DM_CLASSID, &share.ev_share));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode UpdateStressShared(MpmSolver &mpm, const MaterialPointFields &f)
{
  StressShare   &share = mpm.stress_share;
  const PetscInt nmat  = (PetscInt)mpm.materials.size();
  PetscFunctionBeginUser;
  if (!share.enabled || mpm.size == 1) {
    PetscCall(UpdateAllMaterials(mpm, f));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscLogEventBegin(share.ev_share, 0, 0, 0, 0));
  // the plan, the same on every rank, from each rank's count, its measured time per point of its own
  // update (smoothed; counts alone with -mpm_stress_share_balance count) and its sharing overhead: a
  // sender's cost of packing and unpacking a point it sends, as a fraction of updating one (measured
  // on its last sharing step) and, as a receiver, how much longer than their sender a received point
  // takes it (the waits for the messages included; measured on its last receiving step)
  std::vector<ShareLoad> loads(mpm.size);
  const ShareLoad        mine = {(PetscReal)f.n, share.overhead, share.seconds_per_point, share.receive_factor};
  static_assert(sizeof(ShareLoad) == 4 * sizeof(PetscReal), "ShareLoad travels as 4 reals");
  PetscCallMPI(MPI_Allgather(&mine, 4, MPIU_REAL, loads.data(), 4, MPIU_REAL, mpm.comm));
  share.sends.clear();
  share.receives.clear();
  bool by_time = false;
  for (const ShareTransfer &t : StressSharePlan(loads, share.balance == StressShare::Balance::Time, share.threshold, share.min_points, &by_time)) {
    if (t.sender == mpm.rank) share.sends.push_back({t.receiver, (PetscInt)t.count});
    if (t.receiver == mpm.rank) share.receives.push_back({t.sender, (PetscInt)t.count});
    share.point_steps += t.count;
  }
  if (share.sends.empty() && share.receives.empty()) {
    PetscCall(PetscLogEventEnd(share.ev_share, 0, 0, 0, 0));
    const PetscLogDouble start = MPI_Wtime();
    PetscCall(UpdateAllMaterials(mpm, f));
    MeasureCost(share, MPI_Wtime() - start, f.n);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (share.material_fields.empty())
    for (PetscInt id = 0; id < nmat; ++id) share.material_fields.push_back(MaterialStateFields(mpm, *f.state, id));
  std::vector<Block>  blocks;
  std::vector<size_t> offsets;
  size_t              num_outputs;

  const PetscLogDouble pack_start = MPI_Wtime();
  // a sender: points spread evenly over the local array, split among its receivers in order, and
  // each receiver's share by material into messages of at most kChunkPoints
  PetscInt num_sent = 0;
  for (const auto &t : share.sends) num_sent += t.count;
  // (runs of kRun consecutive points, so that the messages copy runs of memory)
  constexpr PetscInt     kRun = 32;
  const PetscInt         runs = (f.n + kRun - 1) / kRun, runs_sent = std::min(runs, (num_sent + kRun - 1) / kRun);
  std::vector<PetscInt> &spread = share.spread;
  spread.clear();
  for (PetscInt r = 0; r < runs && runs_sent; ++r)
    if ((PetscInt64)(r + 1) * runs_sent / runs > (PetscInt64)r * runs_sent / runs)
      for (PetscInt p = r * kRun; p < std::min(f.n, (r + 1) * kRun); ++p) spread.push_back(p);
  spread.resize(std::min<size_t>(spread.size(), num_sent));
  share.selected.clear();
  share.chunks.clear();
  share.headers.assign(share.sends.size(), {});
  std::vector<MPI_Request> send_requests, result_requests;
  for (size_t t = 0, first = 0; t < share.sends.size(); first += share.sends[t].count, ++t)
    for (PetscInt id = 0; id < nmat; ++id) {
      const size_t start = share.selected.size();
      for (size_t j = first; j < std::min(spread.size(), first + share.sends[t].count); ++j)
        if (f.material[spread[j]] == id) share.selected.push_back(spread[j]);
      for (size_t c = start; c < share.selected.size(); c += kChunkPoints) {
        const PetscInt n = (PetscInt)std::min<size_t>(kChunkPoints, share.selected.size() - c);
        share.chunks.push_back({share.sends[t].peer, id, (PetscInt)c, n, (PetscInt)share.headers[t].size() / 2});
        share.headers[t].push_back(id);
        share.headers[t].push_back(n);
      }
    }
  for (size_t t = 0; t < share.sends.size(); ++t) {
    // (MPI guarantees tags up to 32767)
    PetscCheck(kTagResults + (PetscInt)share.headers[t].size() / 2 <= 32767, PETSC_COMM_SELF, PETSC_ERR_SUP, "Stress sharing: %" PetscInt_FMT " messages to one rank exceed the tag range; raise the points per message or use -mpm_stress_share 0",
               (PetscInt)share.headers[t].size() / 2);
    send_requests.emplace_back();
    PetscCallMPI(MPI_Isend(share.headers[t].data(), (int)share.headers[t].size(), MPIU_INT, share.sends[t].peer, kTagHeader, mpm.comm, &send_requests.back()));
  }
  share.out.resize(std::max(share.out.size(), share.chunks.size()));
  share.results.resize(std::max(share.results.size(), share.chunks.size()));
  for (size_t c = 0; c < share.chunks.size(); ++c) {
    const StressShare::Chunk &chunk = share.chunks[c];
    ListBlocks(f, share.material_fields[chunk.material], blocks, &num_outputs);
    Offsets(blocks, chunk.count, offsets);
    share.out[c].resize(offsets.back());
    share.results[c].resize(offsets[num_outputs]);
    for (size_t b = 0; b < blocks.size(); ++b) MoveBlock(blocks[b], share.selected.data() + chunk.first, chunk.count, share.out[c].data() + offsets[b], true);
    result_requests.emplace_back();
    PetscCallMPI(MPI_Irecv(share.results[c].data(), (int)offsets[num_outputs], MPI_BYTE, chunk.peer, kTagResults + chunk.index, mpm.comm, &result_requests.back()));
    send_requests.emplace_back();
    PetscCallMPI(MPI_Isend(share.out[c].data(), (int)offsets.back(), MPI_BYTE, chunk.peer, kTagInputs, mpm.comm, &send_requests.back()));
  }
  // the models skip the sent points (material -1) until their results are back
  PetscInt *material = const_cast<PetscInt *>(f.material);
  for (PetscInt p : share.selected) material[p] = -1;
  PetscLogDouble overhead_seconds = MPI_Wtime() - pack_start;

  // a receiver: the others' points first (their senders wait for them), then its own
  const PetscLogDouble     receive_start = MPI_Wtime();
  std::vector<MPI_Request> header_requests(share.receives.size()), in_requests, back_requests;
  share.received_headers.resize(share.receives.size());
  for (size_t t = 0; t < share.receives.size(); ++t) {
    share.received_headers[t].resize(2 * (share.receives[t].count / kChunkPoints + nmat + 1));
    PetscCallMPI(MPI_Irecv(share.received_headers[t].data(), (int)share.received_headers[t].size(), MPIU_INT, share.receives[t].peer, kTagHeader, mpm.comm, &header_requests[t]));
  }
  std::vector<MPI_Status> header_status(share.receives.size());
  PetscCallMPI(MPI_Waitall((int)header_requests.size(), header_requests.data(), header_status.data()));
  share.incoming.clear();
  for (size_t t = 0; t < share.receives.size(); ++t) {
    int num;
    PetscCallMPI(MPI_Get_count(&header_status[t], MPIU_INT, &num));
    for (int k = 0; k < num / 2; ++k) share.incoming.push_back({share.receives[t].peer, share.received_headers[t][2 * k], 0, share.received_headers[t][2 * k + 1], k});
  }
  share.in.resize(std::max(share.in.size(), share.incoming.size()));
  for (size_t c = 0; c < share.incoming.size(); ++c) {
    ListBlocks(f, share.material_fields[share.incoming[c].material], blocks, &num_outputs);
    Offsets(blocks, share.incoming[c].count, offsets);
    share.in[c].resize(offsets.back());
    in_requests.emplace_back();
    PetscCallMPI(MPI_Irecv(share.in[c].data(), (int)offsets.back(), MPI_BYTE, share.incoming[c].peer, kTagInputs, mpm.comm, &in_requests.back()));
  }
  PetscCall(PetscLogEventEnd(share.ev_share, 0, 0, 0, 0));
  back_requests.resize(share.incoming.size());
  for (size_t done = 0; done < share.incoming.size(); ++done) {
    int c;
    PetscCallMPI(MPI_Waitany((int)in_requests.size(), in_requests.data(), &c, MPI_STATUS_IGNORE));
    const StressShare::Chunk &chunk = share.incoming[c];
    MaterialPointFields       g;
    MaterialState             state;
    ListBlocks(f, share.material_fields[chunk.material], blocks, &num_outputs);
    Offsets(blocks, chunk.count, offsets);
    PetscCall(ViewMessage(f, share.material_fields[chunk.material], chunk.count, share.in[c].data(), offsets, g, state));
    PetscCall(mpm.materials[chunk.material]->UpdateStress(g, chunk.material, mpm.dt));
    PetscCallMPI(MPI_Isend(share.in[c].data(), (int)offsets[num_outputs], MPI_BYTE, chunk.peer, kTagResults + chunk.index, mpm.comm, &back_requests[c]));
  }
  if (by_time && !share.receives.empty()) { // the received points' seconds against their senders'
    PetscReal senders_seconds = 0;
    for (const auto &t : share.receives) senders_seconds += t.count * loads[t.peer].seconds_per_point;
    const PetscLogDouble seconds = MPI_Wtime() - receive_start;
    if (senders_seconds > 0 && seconds > 0) Smooth(share.receive_factor, std::min<PetscReal>(seconds / senders_seconds, 10));
    PetscCall(PetscInfo(nullptr, "stress share: received %g s of the senders' work in %g s: factor %g\n", (double)senders_seconds, seconds, (double)share.receive_factor));
  }
  const PetscLogDouble own_start = MPI_Wtime();
  PetscCall(UpdateAllMaterials(mpm, f));
  const PetscLogDouble own_seconds = MPI_Wtime() - own_start;

  // the results back into the swarm, the materials restored
  PetscCall(PetscLogEventBegin(share.ev_share, 0, 0, 0, 0));
  for (size_t done = 0; done < share.chunks.size(); ++done) {
    int c;
    PetscCallMPI(MPI_Waitany((int)result_requests.size(), result_requests.data(), &c, MPI_STATUS_IGNORE));
    const PetscLogDouble      unpack_start = MPI_Wtime();
    const StressShare::Chunk &chunk        = share.chunks[c];
    const PetscInt           *idx          = share.selected.data() + chunk.first;
    ListBlocks(f, share.material_fields[chunk.material], blocks, &num_outputs);
    Offsets(blocks, chunk.count, offsets);
    for (size_t b = 0; b < num_outputs; ++b) MoveBlock(blocks[b], idx, chunk.count, share.results[c].data() + offsets[b], false);
    for (PetscInt j = 0; j < chunk.count; ++j) material[idx[j]] = chunk.material;
    overhead_seconds += MPI_Wtime() - unpack_start;
  }
  // a sender's overhead per point sent against its update per point kept, smoothed over steps
  const PetscInt kept = f.n - (PetscInt)share.selected.size();
  MeasureCost(share, own_seconds, kept);
  if (!share.selected.empty() && kept > 0 && own_seconds > 0) {
    const PetscReal ratio = (overhead_seconds / share.selected.size()) / (own_seconds / kept);
    Smooth(share.overhead, std::min<PetscReal>(0.8, ratio));
    PetscCall(PetscInfo(nullptr, "stress share: sent %zu, kept %" PetscInt_FMT ": overhead %g s, own %g s, ratio %g\n", share.selected.size(), kept, overhead_seconds, own_seconds, (double)ratio));
  }
  PetscCallMPI(MPI_Waitall((int)send_requests.size(), send_requests.data(), MPI_STATUSES_IGNORE));
  PetscCallMPI(MPI_Waitall((int)back_requests.size(), back_requests.data(), MPI_STATUSES_IGNORE));
  PetscCall(PetscLogEventEnd(share.ev_share, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
