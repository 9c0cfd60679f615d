#pragma once

// The two small 2D plane-strain scenes on which tests/primal compares the
// primal Uzawa-CGC method with the dual solvers (uzawa_vs_dual,
// report_rules): a block on a rigid plane and a block pressed onto a
// clamped block, each with the friction law it is given.

#include <deal.II/base/function.h>

#include <contact/contact_discretization.h>
#include <contact/contact_pair.h>
#include <contact/friction_law.h>
#include <contact/rigid_obstacle.h>
#include <contact/unit_box.h>
#include <fem/elastic_body.h>

#include <algorithm>
#include <memory>
#include <vector>

namespace block_scenes
{
  using namespace dealii;
  using namespace dualcontact;

  struct Scene
  {
    std::vector<std::unique_ptr<fem::ElasticBody<2>>>  bodies;
    std::vector<const fem::ElasticBody<2> *>           pointers;
    std::unique_ptr<contact::ContactDiscretization<2>> contact;
  };

  inline fem::DirichletCondition<2>
  moved(const types::boundary_id id, const double dx, const double dy)
  {
    return {id,
            ComponentMask(2, true),
            std::make_shared<Functions::ConstantFunction<2>>(
              std::vector<double>{dx, dy})};
  }

  inline void
  finish(Scene &scene, const contact::ContactPair<2> &pair)
  {
    for (auto &b : scene.bodies)
    {
      b->setup();
      b->assemble();
      scene.pointers.push_back(b.get());
    }
    scene.contact = std::make_unique<contact::ContactDiscretization<2>>(
      scene.pointers, std::vector<contact::ContactPair<2>>{pair});
  }

  inline contact::FrictionLaw
  friction_law(const contact::FrictionLaw::Type type, const double value)
  {
    contact::FrictionLaw f;
    f.type  = type;
    f.first = value;
    return f;
  }

  // block [0,1]^2 (6 x 6 Q1) on the plane y = 0, its top face moved down
  // and sideways
  inline Scene
  block_on_plane(const contact::FrictionLaw &friction)
  {
    Scene scene;
    scene.bodies.push_back(make_unit_box<2>("block", 0., 6, 1, 1e9));
    scene.bodies[0]->set_dirichlet_conditions({moved(3, 2e-4, -1e-3)});
    contact::ContactPair<2> pair;
    pair.name           = "block-plane";
    pair.slave_boundary = 2;
    pair.obstacle =
      std::make_shared<contact::PlaneObstacle<2>>(Point<2>(0., 0.),
                                                  Tensor<1, 2>({0., 1.}));
    pair.friction = friction;
    finish(scene, pair);
    return scene;
  }

  // block [0,1]x[0,1] (4 x 4) on a clamped block [0,1]x[-1,0] (5 x 5), its
  // top face moved down and sideways (non-matching meshes)
  inline Scene
  two_blocks(const contact::FrictionLaw &friction)
  {
    Scene scene;
    scene.bodies.push_back(make_unit_box<2>("lower", -1., 5, 1, 2e9));
    scene.bodies.push_back(make_unit_box<2>("upper", 0., 4, 1, 1e9));
    scene.bodies[0]->set_dirichlet_conditions({moved(2, 0., 0.)});
    scene.bodies[1]->set_dirichlet_conditions({moved(3, 3e-4, -1e-3)});
    contact::ContactPair<2> pair;
    pair.name            = "upper-lower";
    pair.slave_body      = 1;
    pair.slave_boundary  = 2;
    pair.master_body     = 0;
    pair.master_boundary = 3;
    pair.friction        = friction;
    finish(scene, pair);
    return scene;
  }

  // ||a - b||_inf / ||b||_inf
  inline double
  relative_difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> d(a);
    d -= b;
    return d.linfty_norm() / b.linfty_norm();
  }

  // max_k ||a_k - b_k||_inf / max_k ||b_k||_inf
  inline double
  relative_difference(const std::vector<Vector<double>> &a,
                      const std::vector<Vector<double>> &b)
  {
    double diff = 0., norm = 0.;
    for (unsigned int k = 0; k < a.size(); ++k)
    {
      Vector<double> d(a[k]);
      d -= b[k];
      diff = std::max(diff, d.linfty_norm());
      norm = std::max(norm, b[k].linfty_norm());
    }
    return diff / norm;
  }
} // namespace block_scenes
