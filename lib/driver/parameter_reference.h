/**
 * @file parameter_reference.h
 * What `dualcontact --print-parameters' prints: every parameter a scene can
 * set, with its default, its pattern and its documentation, as a parameter
 * file or as JSON (from which scripts/parameter_reference writes the
 * manual's reference, doc/manual/reference/parameters.md).
 */
#ifndef dualcontact_driver_parameter_reference_h
#define dualcontact_driver_parameter_reference_h

#include <deal.II/base/parameter_handler.h>

#include <driver/scene_layout.h>

#include <ostream>
#include <string>

namespace dualcontact
{
  namespace driver
  {
    /**
     * The parameters of a representative scene: 3D, one body (one
     * material; `Dirichlet 1' and `Traction 1' are declared anyway), one
     * obstacle and one contact pair.  Their numbered subsections (`Body 1',
     * `Body 1/Material 1', ...) stand for every subsection of their kind:
     * `Body 2', ... have the same entries.  In 2D the vector entries have
     * two components (their defaults too).
     *
     * The JSON form is one object: `program', `version', `dimension',
     * `repeated_subsections' (per numbered subsection: its path as
     * declared, e.g. "Body 1/Material 1", the path it stands for, "Body
     * N/Material M", and the entry that counts them) and `parameters', the
     * top level as a subsection: `entries' (per entry `name', `default',
     * `pattern', `documentation') and `subsections' (per subsection
     * `name', `entries', `subsections'), each in declaration order.
     */
    class ParameterReference
    {
    public:
      enum class Format
      {
        prm,
        json
      };

      /**
       * "prm" or "json" (the text after `--print-parameters='); throws an
       * ExcMessage naming both for anything else.
       */
      static Format
      parse_format(const std::string &name);

      /** The layout whose parameters are printed. */
      static SceneLayout
      representative_layout();

      /** Print the reference in @p format. */
      static void
      print(std::ostream &out, const Format format);

    private:
      static void
      print_prm(const dealii::ParameterHandler &prm, std::ostream &out);

      static void
      print_json(const dealii::ParameterHandler &prm, std::ostream &out);
    };
  } // namespace driver
} // namespace dualcontact

#endif
