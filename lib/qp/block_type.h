/**
 * @file block_type.h
 * The kinds of blocks a SeparableSet is made of (one type each in
 * qp/blocks/), as a value for counts and reports.
 */
#ifndef dualcontact_qp_block_type_h
#define dualcontact_qp_block_type_h

#include <util/enum_names.h>

namespace dualcontact
{
  namespace qp
  {
    /// The kinds of blocks a SeparableSet is made of.
    enum class BlockType
    {
      /// x_i >= l
      bound,
      /// l <= x_i <= u
      box,
      /// ||(x_f, x_{f+1})|| <= r
      disc,
      /// (x_f/a)^2 + (x_{f+1}/b)^2 <= 1 in a frame rotated by an angle
      ellipse,
      /// ||(x_{f+1}, x_{f+2})|| <= mu x_f  (normal component first)
      cone
    };

    /// Number of BlockType values (for arrays indexed by type).
    constexpr unsigned int n_block_types = 5;

    /// The names of BlockType in reports: "bound", "box", "disc", "ellipse",
    /// "cone".
    inline constexpr util::EnumNames<BlockType, n_block_types> block_type_names{
      "block type",
      {{"bound", "box", "disc", "ellipse", "cone"}},
    };
  } // namespace qp
} // namespace dualcontact

#endif
