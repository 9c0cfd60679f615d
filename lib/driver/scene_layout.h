#pragma once

#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /** How many subsections of each kind one body has. */
    struct BodyLayout
    {
      unsigned int n_materials = 1;
      unsigned int n_dirichlet = 0;
      unsigned int n_tractions = 0;

      bool
      operator==(const BodyLayout &other) const
      {
        return n_materials == other.n_materials &&
               n_dirichlet == other.n_dirichlet &&
               n_tractions == other.n_tractions;
      }
    };

    /**
     * The shape of a parameter file: the dimension, per body how many
     * `Material N', `Dirichlet N' and `Traction N' subsections exist, and
     * how many `Obstacle N' and `Contact pair N' subsections.  It is
     * read from the file itself in passes that ignore everything else (see
     * SceneParameters::read()), so that a scene has any number of bodies,
     * materials and boundary conditions.
     */
    struct SceneLayout
    {
      unsigned int            dimension = 3;
      std::vector<BodyLayout> bodies    = {BodyLayout()};
      /** Number of `Obstacle N' subsections. */
      unsigned int n_obstacles = 0;
      /** Number of `Contact pair N' subsections. */
      unsigned int n_contact_pairs = 0;
    };
  } // namespace driver
} // namespace dualcontact
