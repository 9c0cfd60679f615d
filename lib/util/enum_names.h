/**
 * @file enum_names.h
 * The names of an enumeration's values in parameter files, reports and
 * command lines: one table gives both directions and the list of choices,
 * so the three cannot disagree.
 */
#ifndef dualcontact_util_enum_names_h
#define dualcontact_util_enum_names_h

#include <deal.II/base/exceptions.h>

#include <array>
#include <cstddef>
#include <string>

namespace dualcontact
{
  namespace util
  {
    /// One value and a further spelling of its name.
    template <typename Enum>
    struct EnumAlias
    {
      Enum        value;
      const char *name;
    };

    /**
     * The names of the @p N values of @p Enum, whose values must be the
     * default ones 0, 1, ..., N - 1 (the i-th name is that of value i), and
     * @p A further spellings that value() accepts too (e.g. an old name).
     * @p what names the setting in errors ("unknown <what> `x' (a | b)").
     */
    template <typename Enum, std::size_t N, std::size_t A = 0>
    struct EnumNames
    {
      const char                    *what;
      std::array<const char *, N>    names;
      std::array<EnumAlias<Enum>, A> aliases = {};

      /// The name of @p value.
      const char *
      name(const Enum value) const
      {
        const std::size_t i = static_cast<std::size_t>(value);
        Assert(i < N, dealii::ExcIndexRange(i, 0, N));
        return names[i];
      }

      /// The value named @p text; throws naming `what` and the choices.
      Enum
      value(const std::string &text) const
      {
        for (std::size_t i = 0; i < N; ++i)
          if (text == names[i])
            return static_cast<Enum>(i);
        for (const EnumAlias<Enum> &alias : aliases)
          if (text == alias.name)
            return alias.value;
        AssertThrow(false,
                    dealii::ExcMessage("unknown " + std::string(what) + " `" +
                                       text + "' (" + choices(" | ") + ")"));
        return static_cast<Enum>(0);
      }

      /// The names (without the aliases) joined by @p separator.
      std::string
      choices(const char *separator = "|") const
      {
        std::string text;
        for (const char *name : names)
          text += (text.empty() ? "" : separator) + std::string(name);
        return text;
      }
    };
  } // namespace util
} // namespace dualcontact

#endif
