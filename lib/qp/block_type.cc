#include <qp/block_type.h>

namespace dualcontact
{
  namespace qp
  {
    const char *
    block_type_name(const BlockType type)
    {
      switch (type)
      {
        case BlockType::bound:
          return "bound";
        case BlockType::box:
          return "box";
        case BlockType::disc:
          return "disc";
        case BlockType::ellipse:
          return "ellipse";
        case BlockType::cone:
          return "cone";
      }
      return "unknown";
    }
  } // namespace qp
} // namespace dualcontact
