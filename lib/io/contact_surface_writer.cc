#include <io/contact_surface_writer.h>

#include <iomanip>
#include <map>

namespace dualcontact
{
  namespace io
  {
    namespace
    {
      template <int dim>
      void
      write_vector(std::ostream &out, const dealii::Tensor<1, dim> &v)
      {
        for (unsigned int d = 0; d < 3; ++d)
          out << (d == 0 ? "" : " ") << (d < dim ? v[d] : 0.);
        out << "\n";
      }
    } // namespace


    template <int dim>
    void
    write_contact_surface(std::ostream                               &out,
                          const std::vector<ContactSurfaceNode<dim>> &nodes)
    {
      const std::size_t n = nodes.size();
      out << std::setprecision(12);
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
             "byte_order=\"LittleEndian\">\n"
          << "<UnstructuredGrid>\n"
          << "<Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n
          << "\">\n";
      out << "<Points>\n<DataArray type=\"Float64\" "
             "NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (const auto &node : nodes)
        write_vector<dim>(out, dealii::Tensor<1, dim>(node.position));
      out << "</DataArray>\n</Points>\n";
      out << "<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
             "format=\"ascii\">\n";
      for (std::size_t i = 0; i < n; ++i)
        out << i << "\n";
      out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
             "format=\"ascii\">\n";
      for (std::size_t i = 0; i < n; ++i)
        out << i + 1 << "\n";
      out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
             "format=\"ascii\">\n";
      for (std::size_t i = 0; i < n; ++i)
        out << "1\n"; // VTK_VERTEX
      out << "</DataArray>\n</Cells>\n";

      out << "<PointData Scalars=\"pressure_Pa\">\n";
      const auto scalar = [&](const std::string &name, const auto &value)
      {
        out << "<DataArray type=\"Float64\" Name=\"" << name
            << "\" format=\"ascii\">\n";
        for (const auto &node : nodes)
          out << value(node) << "\n";
        out << "</DataArray>\n";
      };
      const auto vector = [&](const std::string &name, const auto &value)
      {
        out << "<DataArray type=\"Float64\" Name=\"" << name
            << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
        for (const auto &node : nodes)
          write_vector<dim>(out, value(node));
        out << "</DataArray>\n";
      };
      scalar("pressure_Pa", [](const auto &node) { return node.pressure; });
      vector("tangential_traction_Pa",
             [](const auto &node) { return node.tangential_traction; });
      vector("slip_m", [](const auto &node) { return node.slip; });
      scalar("gap_m", [](const auto &node) { return node.gap; });
      scalar("weight", [](const auto &node) { return node.weight; });
      out << "<DataArray type=\"Int32\" Name=\"status\" format=\"ascii\">\n";
      for (const auto &node : nodes)
        out << node.status << "\n";
      out << "</DataArray>\n";
      vector("normal", [](const auto &node) { return node.normal; });
      out << "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    }


    void
    write_pvd(std::ostream                                      &out,
              const std::vector<std::pair<double, std::string>> &entries)
    {
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"Collection\" version=\"0.1\" "
             "byte_order=\"LittleEndian\">\n"
          << "  <Collection>\n";
      std::map<double, unsigned int> parts;
      for (const auto &[time, file] : entries)
        out << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\""
            << parts[time]++ << "\" file=\"" << file << "\"/>\n";
      out << "  </Collection>\n</VTKFile>\n";
    }


    template void
    write_contact_surface<2>(std::ostream &,
                             const std::vector<ContactSurfaceNode<2>> &);
    template void
    write_contact_surface<3>(std::ostream &,
                             const std::vector<ContactSurfaceNode<3>> &);
  } // namespace io
} // namespace dualcontact
