// ClothModel's part of a checkpoint: the terms' carried state (the shell's director
// references) and the fingerprint of the mesh and its partition. The mesh itself is not
// stored: a restart builds it again from the same mesh file and parameters (reading and
// partitioning are deterministic), and the fingerprint proves it is the same.

#include <deal.II/base/mpi.h>

#include "io/collective.h"
#include "io/input_error.h"
#include "scene/cloth_model.h"

#include <cstdint>
#include <cstring>
#include <sstream>

namespace clothsim
{
  namespace
  {
    // FNV-1a over the bytes of a value.
    template <typename T>
    void
    hash_value(std::uint64_t &hash, const T &value)
    {
      unsigned char bytes[sizeof(T)];
      std::memcpy(bytes, &value, sizeof(T));
      for (const unsigned char c : bytes)
        {
          hash ^= c;
          hash *= 1099511628211ull;
        }
    }
  } // namespace


  std::vector<double>
  ClothModel::fingerprint() const
  {
    std::uint64_t hash = 14695981039346656037ull;
    for (const mesh::Discretization::Element &element : discretization.elements())
      {
        for (const types::global_dof_index dof : element.dofs)
          hash_value(hash, static_cast<std::uint64_t>(dof));
        for (const Point<3> &corner : element.reference)
          for (unsigned int c = 0; c < 3; ++c)
            hash_value(hash, corner[c]);
      }
    for (const types::global_dof_index dof : owned_dofs())
      hash_value(hash, static_cast<std::uint64_t>(dof));
    return {double(Utilities::MPI::n_mpi_processes(get_communicator())),
            double(n_dofs()),
            double(owned_dofs().n_elements()),
            double(discretization.elements().size()),
            double(hash >> 32),
            double(hash & 0xffffffffu)};
  }


  void
  ClothModel::save_state(io::CheckpointData &rank) const
  {
    rank.set("model fingerprint", fingerprint());
    for (const physics::Term *term : model->terms())
      {
        const std::vector<double> state = term->saved_state();
        if (!state.empty())
          rank.set("term " + term->name(), state);
      }
  }


  void
  ClothModel::restore_state(const io::CheckpointData &rank)
  {
    const std::vector<double>  expected = fingerprint();
    const std::vector<double> &saved    = rank.get("model fingerprint", expected.size());
    // Any rank's mismatch stops all of them.
    if (!io::on_all_ranks(saved == expected, get_communicator()))
      {
        std::ostringstream message;
        message << "the checkpoint was written for another mesh or partition ("
                << saved[1] << " unknowns, here " << expected[1]
                << "; or a changed mesh file): restart with the run's mesh and "
                   "parameters";
        throw InputError(rank.get_source(), "", message.str());
      }
    for (physics::Term *term : model->terms())
      if (rank.has("term " + term->name()))
        term->restore_state(rank.get("term " + term->name()));
      else if (!term->saved_state().empty())
        throw InputError(rank.get_source(),
                         "",
                         "the checkpoint has no state of the term " + term->name());
  }
} // namespace clothsim
