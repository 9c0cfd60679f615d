#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    /**
     * What the contact-surface file shows at one contact node (all in the
     * reference configuration, SI units; 2D: per metre of thickness).
     */
    template <int dim>
    struct ContactSurfaceNode
    {
      dealii::Point<dim> position;
      /** Unit normal, from the slave into the master [-]. */
      dealii::Tensor<1, dim> normal;
      /** lambda_N / w [Pa]: the normal contact pressure. */
      double pressure = 0;
      /** sum_k lambda_T,k t_k / w [Pa]: the tangential traction. */
      dealii::Tensor<1, dim> tangential_traction;
      /** sum_k (B_T u + o_T)_k t_k [m]: relative tangential displacement. */
      dealii::Tensor<1, dim> slip;
      /** c - B_N u [m]: the gap after deformation (0 where in contact). */
      double gap = 0;
      /** 0 separated, 1 stick, 2 slip. */
      int status = 0;
    };


    /**
     * Write the contact nodes of one pair as a VTK XML unstructured grid
     * (ASCII .vtu, one vertex cell per node), with the point fields
     * `pressure_Pa', `tangential_traction_Pa' (vector), `slip_m' (vector),
     * `gap_m', `status' (0 separated, 1 stick, 2 slip) and `normal'
     * (vector).  Vectors have three components (z = 0 in 2D), as VTK
     * expects.  Written by hand rather than through VTK so that the file
     * is the same with or without VTK and needs no mesh object.
     */
    template <int dim>
    void
    write_contact_surface(std::ostream                               &out,
                          const std::vector<ContactSurfaceNode<dim>> &nodes);

    /**
     * A PVD collection: each entry (time, file name) becomes a data set;
     * entries with equal time are parts of one step.
     */
    void
    write_pvd(std::ostream                                      &out,
              const std::vector<std::pair<double, std::string>> &entries);
  } // namespace io
} // namespace dualcontact
