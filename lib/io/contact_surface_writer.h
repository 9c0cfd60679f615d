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
     * The values of the `status' field of the contact-surface file.  A
     * node is separated when its normal multiplier is not above the status
     * tolerance times the pair's largest one.  A node in contact under a
     * friction law (Tresca, Coulomb) sticks while its tangential
     * multiplier is inside the slip bound and slips on it; a node in
     * contact under a frictionless law has no tangential multiplier, so it
     * neither sticks nor slips: it has its own value.
     */
    namespace contact_status
    {
      /** No contact pressure (up to the status tolerance). */
      constexpr int separated = 0;
      /** In contact, tangential multiplier strictly inside the slip bound. */
      constexpr int stick = 1;
      /** In contact, tangential multiplier on the slip bound. */
      constexpr int slip = 2;
      /** In contact, frictionless pair (no tangential multiplier). */
      constexpr int frictionless_contact = 3;
    } // namespace contact_status


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
      /**
       * Contact area weight w = int phi ds over the slave surface [m^2; m
       * in 2D]: pressure * weight is the nodal force lambda_N, and the w
       * are the weights of the nodal quadrature on the contact surface
       * (e.g. for pressure errors against a closed form).
       */
      double weight = 0;
      /** A contact_status value: 0 separated, 1 stick, 2 slip, 3
       * frictionless contact. */
      int status = contact_status::separated;
    };


    /**
     * Write the contact nodes of one pair as a VTK XML unstructured grid
     * (ASCII .vtu, one vertex cell per node), with the point fields
     * `pressure_Pa', `tangential_traction_Pa' (vector), `slip_m' (vector),
     * `gap_m', `weight' (the area weight w: m^2 in 3D, m in 2D),
     * `status' (contact_status: 0 separated, 1 stick, 2 slip, 3 in
     * contact on a frictionless pair) and `normal' (vector).  Vectors have
     * three components (z = 0 in 2D), as VTK expects.  Written by hand rather
     * than through VTK so that the file is the same with or without VTK and
     * needs no mesh object.
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
