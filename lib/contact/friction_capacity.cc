#include <contact/friction_capacity.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace dualcontact
{
  namespace contact
  {
    namespace
    {
      /** "(x, y)" with 4 digits, no "-0". */
      template <int dim>
      std::string
      vector_text(const dealii::Tensor<1, dim> &v, const double scale)
      {
        std::ostringstream out;
        out << std::setprecision(4) << "(";
        for (unsigned int d = 0; d < dim; ++d)
          out << (d == 0 ? "" : ", ")
              << (std::abs(v[d]) <= 1e-12 * scale ? 0. : v[d]);
        out << ")";
        return out.str();
      }
    } // namespace


    template <int dim>
    FrictionCapacity<dim>::FrictionCapacity(
      const ContactDiscretization<dim> &contact,
      const std::vector<Body>          &bodies)
        : contact_(contact)
        , bodies_(bodies)
    {
      for (unsigned int b = 0; b < bodies_.size(); ++b)
        if (bodies_[b].floating)
        {
          const std::string finding = check_body(b);
          if (!finding.empty())
            findings_.push_back(finding);
        }
    }


    template <int dim>
    const std::vector<std::string> &
    FrictionCapacity<dim>::findings() const
    {
      return findings_;
    }


    template <int dim>
    std::string
    FrictionCapacity<dim>::check_body(const unsigned int b) const
    {
      // the body's contact nodes with the normal as seen from the body
      // (pointing out of it, into what holds it), one common normal or none
      dealii::Tensor<1, dim>    normal;
      bool                      first      = true;
      double                    largest_mu = 0, tresca_capacity = 0;
      bool                      coulomb = false, tresca = false;
      std::vector<unsigned int> pairs;
      for (const ContactNode<dim> &node : contact_.nodes())
      {
        const ContactPair<dim> &pair = contact_.pairs()[node.pair];
        double                  side = 0;
        if (pair.slave_body == b)
          side = 1;
        else if (!pair.obstacle && pair.master_body == b)
          side = -1;
        else
          continue;
        const dealii::Tensor<1, dim> n = side * node.normal;
        if (first)
          normal = n;
        else if (n * normal < 1 - 1e-6)
          return ""; // curved or two-sided: normal forces carry load too
        first = false;
        if (std::find(pairs.begin(), pairs.end(), node.pair) == pairs.end())
          pairs.push_back(node.pair);
        const FrictionLaw &law = pair.friction;
        if (law.is_coulomb())
        {
          coulomb    = true;
          largest_mu = std::max({largest_mu, law.first, law.second});
        }
        else if (law.has_friction())
        {
          tresca = true;
          tresca_capacity += std::max(law.first, law.second) * node.weight;
        }
      }
      if (first || (!coulomb && !tresca))
        return "";

      const dealii::Tensor<1, dim> load   = bodies_[b].load;
      const double                 N      = load * normal;
      const dealii::Tensor<1, dim> T      = load - N * normal;
      const double                 T_norm = T.norm();
      const double                 scale  = load.norm();
      const char                  *unit   = dim == 2 ? " N/m" : " N";
      std::string                  in_pairs;
      for (const unsigned int p : pairs)
        in_pairs += (in_pairs.empty() ? "" : ", ") + std::to_string(p + 1);
      std::ostringstream out;
      out << std::setprecision(4);
      if (N <= 1e-12 * scale)
      {
        if (scale == 0)
          return "";
        out << "No equilibrium: the load on " << bodies_[b].name << ", "
            << vector_text(load, scale) << unit
            << ", pulls it off its contact (normal component " << N << unit
            << " along the contact normal " << vector_text(normal, 1.)
            << " of contact pair " << in_pairs
            << "); a floating body needs a load pressing it onto its masters";
        return out.str();
      }
      // Coulomb: mu N; Tresca: the bound times the area (a scene may mix)
      const double capacity = (coulomb ? largest_mu * N : 0.) + tresca_capacity;
      if (!(T_norm > capacity * (1 + 1e-6)))
        return "";
      out << "No equilibrium: the tangential load on " << bodies_[b].name
          << ", " << T_norm << unit << " (the load " << vector_text(load, scale)
          << unit << " less its normal part " << N << unit << " along "
          << vector_text(normal, 1.)
          << "), exceeds the friction capacity of contact pair"
          << (pairs.size() > 1 ? "s " : " ") << in_pairs << ", " << capacity
          << unit << " (";
      if (coulomb)
        out << "Coulomb: friction coefficient " << largest_mu
            << " x normal load " << N << unit;
      if (coulomb && tresca)
        out << " + ";
      if (tresca)
        out << "Tresca: slip bound x contact area = " << tresca_capacity
            << unit;
      out << "): the body would slide away, no static solution exists";
      return out.str();
    }


    template class FrictionCapacity<2>;
    template class FrictionCapacity<3>;
  } // namespace contact
} // namespace dualcontact
