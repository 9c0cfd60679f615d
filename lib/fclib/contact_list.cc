#include <deal.II/base/exceptions.h>

#include <fclib/contact_list.h>

#include <cmath>

namespace dualcontact
{
  namespace fclib
  {
    ContactList::ContactList(const unsigned int         spacedim,
                             const std::vector<double> &mu,
                             const std::string         &title)
        : spacedim_(spacedim)
        , mu_(mu)
        , title_(title)
    {
      AssertThrow(spacedim == 2 || spacedim == 3,
                  dealii::ExcMessage("FCLIB problem: space dimension " +
                                     std::to_string(spacedim) +
                                     ", expected 2 or 3"));
      for (const double m : mu)
        AssertThrow(m >= 0 && std::isfinite(m),
                    dealii::ExcMessage(
                      "FCLIB problem: negative or non-finite friction "
                      "coefficient mu = " +
                      std::to_string(m)));
    }


    unsigned int
    ContactList::spacedim() const
    {
      return spacedim_;
    }


    unsigned int
    ContactList::n_contacts() const
    {
      return mu_.size();
    }


    unsigned int
    ContactList::n_contact_unknowns() const
    {
      return spacedim_ * mu_.size();
    }


    const std::vector<double> &
    ContactList::mu() const
    {
      return mu_;
    }


    const std::string &
    ContactList::title() const
    {
      return title_;
    }
  } // namespace fclib
} // namespace dualcontact
