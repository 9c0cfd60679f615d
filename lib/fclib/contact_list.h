#pragma once

#include <string>
#include <vector>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * What the local and the global FCLIB problems share: the space
     * dimension, one friction coefficient per contact (unknowns [n, t_1(,
     * t_2)] per contact, normal first) and the title of the file.
     *
     * Why a base class: both forms check the same things on construction
     * (dimension 2 or 3, mu >= 0 and finite) and answer the same questions;
     * written once here, the error messages are the same for both.
     */
    class ContactList
    {
    public:
      ContactList() = default;
      /** Throws unless @p spacedim is 2 or 3 and every mu is >= 0, finite. */
      ContactList(const unsigned int         spacedim,
                  const std::vector<double> &mu,
                  const std::string         &title);

      unsigned int
      spacedim() const;
      unsigned int
      n_contacts() const;
      /** spacedim() * n_contacts(): the number of contact unknowns. */
      unsigned int
      n_contact_unknowns() const;
      const std::vector<double> &
      mu() const;
      const std::string &
      title() const;

    private:
      unsigned int        spacedim_ = 3;
      std::vector<double> mu_;
      std::string         title_;
    };
  } // namespace fclib
} // namespace dualcontact
