#pragma once

#include <deal.II/base/types.h>

#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /** An entry of a row of B before condensation: (body, body dof,
     * coefficient). */
    struct RowEntry
    {
      unsigned int                    body;
      dealii::types::global_dof_index dof;
      double                          value;
    };


    /**
     * What a discretization (NodeToSegment, MortarCoupling) gives a slave
     * node's rows beside the node's own dofs: the master's coefficients
     * (body, dof, coefficient) with each one's vector component, entering
     * the row with a minus sign (node to segment: the master's shape
     * functions at the closest point; mortar: M_jl / S~_j, and at the
     * parent of hanging slave nodes their slave terms as negative
     * entries of the slave body), and the coefficient of the node's own
     * displacement (1; mortar: S_j / S~_j).
     */
    struct MasterEntries
    {
      std::vector<RowEntry>     entries;
      std::vector<unsigned int> components;
      double                    own = 1;
    };
  } // namespace contact
} // namespace dualcontact
