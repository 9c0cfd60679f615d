#include <io/contact_surface_writer.h>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>

namespace dualcontact
{
  namespace io
  {
    namespace
    {
      /** A point field of the contact-surface file. */
      struct Field
      {
        const char  *name;
        const char  *vtk_type;
        unsigned int n_components;
      };

      /** The point fields, in the order of the file. */
      constexpr std::array<Field, 9> fields = {
        {{"pressure_Pa", "Float64", 1},
         {"normal_force_N", "Float64", 1},
         {"area_weight_m2", "Float64", 1},
         {"gap_m", "Float64", 1},
         {"tangential_traction_Pa", "Float64", 3},
         {"slip_m", "Float64", 3},
         {"status", "Int32", 1},
         {"normal", "Float64", 3},
         {"slip_increment_m", "Float64", 3}}};

      /** The values of one point of the file (3 components per vector). */
      struct PointValues
      {
        double                pressure = 0, force = 0, weight = 0, gap = 0;
        std::array<double, 3> traction{}, slip{}, normal{}, increment{};
        int                   status = contact_status::no_contact_node;
      };

      template <int dim>
      void
      add_scaled(std::array<double, 3>        &to,
                 const double                  factor,
                 const dealii::Tensor<1, dim> &tensor)
      {
        for (unsigned int d = 0; d < dim; ++d)
          to[d] += factor * tensor[d];
      }

      /**
       * A contact node's values, or the combination of the nodes'
       * (hanging node; no weight or force of its own), or pressure 0 and
       * gap NaN at a point that is no combination of contact nodes.
       */
      template <int dim>
      PointValues
      point_values(
        const typename ContactSurfaceMesh<dim>::Combination &combination,
        const std::vector<ContactSurfaceNode<dim>>          &nodes,
        const bool                                           is_contact_node)
      {
        PointValues values;
        if (combination.empty())
        {
          values.gap = std::numeric_limits<double>::quiet_NaN();
          return values;
        }
        for (const auto &[i, coefficient] : combination)
        {
          const ContactSurfaceNode<dim> &node = nodes[i];
          values.pressure += coefficient * node.pressure;
          values.gap += coefficient * node.gap;
          add_scaled<dim>(values.traction,
                          coefficient,
                          node.tangential_traction);
          add_scaled<dim>(values.slip, coefficient, node.slip);
          add_scaled<dim>(values.increment, coefficient, node.slip_increment);
          add_scaled<dim>(values.normal, coefficient, node.normal);
        }
        if (is_contact_node)
        {
          const ContactSurfaceNode<dim> &node = nodes[combination[0].first];
          values.weight                       = node.weight;
          values.force                        = node.pressure * node.weight;
          values.status                       = node.status;
        }
        return values;
      }

      vtkSmartPointer<vtkDataArray>
      make_array(const Field &field)
      {
        vtkSmartPointer<vtkDataArray> array;
        if (std::string(field.vtk_type) == "Int32")
          array = vtkSmartPointer<vtkIntArray>::New();
        else
          array = vtkSmartPointer<vtkDoubleArray>::New();
        array->SetName(field.name);
        array->SetNumberOfComponents(field.n_components);
        return array;
      }
    } // namespace


    template <int dim>
    void
    write_contact_surface(std::ostream                               &out,
                          const ContactSurfaceMesh<dim>              &mesh,
                          const std::vector<ContactSurfaceNode<dim>> &nodes,
                          const unsigned int                          piece)
    {
      // the cells of the piece and the points they use, numbered anew
      std::map<unsigned int, vtkIdType> local_point;
      std::vector<unsigned int>         used_points;
      auto             cells = vtkSmartPointer<vtkCellArray>::New();
      std::vector<int> cell_types;
      for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        if (piece != dealii::numbers::invalid_unsigned_int &&
            mesh.owner(c) != piece)
          continue;
        std::vector<vtkIdType> ids(mesh.cell(c).size());
        for (unsigned int v = 0; v < ids.size(); ++v)
        {
          const unsigned int point = mesh.cell(c)[v];
          const auto [it, inserted] =
            local_point.emplace(point, used_points.size());
          if (inserted)
            used_points.push_back(point);
          ids[v] = it->second;
        }
        cells->InsertNextCell(ids.size(), ids.data());
        cell_types.push_back(ids.size() == 2 ? VTK_LINE :
                             ids.size() == 3 ? VTK_TRIANGLE :
                                               VTK_QUAD);
      }

      auto points = vtkSmartPointer<vtkPoints>::New();
      points->SetDataTypeToDouble();
      std::vector<vtkSmartPointer<vtkDataArray>> arrays;
      for (const Field &field : fields)
        arrays.push_back(make_array(field));
      for (const unsigned int point : used_points)
      {
        std::array<double, 3> x{};
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = mesh.position(point)[d];
        points->InsertNextPoint(x.data());
        const PointValues v = point_values<dim>(mesh.combination(point),
                                                nodes,
                                                mesh.is_contact_node(point));
        arrays[0]->InsertNextTuple1(v.pressure);
        arrays[1]->InsertNextTuple1(v.force);
        arrays[2]->InsertNextTuple1(v.weight);
        arrays[3]->InsertNextTuple1(v.gap);
        arrays[4]->InsertNextTuple(v.traction.data());
        arrays[5]->InsertNextTuple(v.slip.data());
        arrays[6]->InsertNextTuple1(v.status);
        arrays[7]->InsertNextTuple(v.normal.data());
        arrays[8]->InsertNextTuple(v.increment.data());
      }

      auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
      grid->SetPoints(points);
      grid->SetCells(cell_types.data(), cells);
      for (const auto &array : arrays)
        grid->GetPointData()->AddArray(array);
      grid->GetPointData()->SetActiveScalars("pressure_Pa");

      auto writer = vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
      writer->SetInputData(grid);
      writer->SetWriteToOutputString(true);
      writer->SetDataModeToBinary();
      writer->SetCompressorTypeToZLib();
      writer->SetHeaderTypeToUInt64();
      AssertThrow(writer->Write() == 1,
                  dealii::ExcMessage("VTK could not write a contact surface"));
      out << writer->GetOutputString();
    }


    void
    write_contact_surface_record(std::ostream                   &out,
                                 const std::vector<std::string> &pieces)
    {
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
             "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
          << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
          << "    <PPointData Scalars=\"pressure_Pa\">\n";
      for (const Field &field : fields)
        out << "      <PDataArray type=\"" << field.vtk_type << "\" Name=\""
            << field.name << "\""
            << (field.n_components > 1 ?
                  " NumberOfComponents=\"" +
                    std::to_string(field.n_components) + "\"" :
                  std::string())
            << "/>\n";
      out << "    </PPointData>\n"
          << "    <PPoints>\n"
          << "      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
          << "    </PPoints>\n";
      for (const auto &piece : pieces)
        out << "    <Piece Source=\"" << piece << "\"/>\n";
      out << "  </PUnstructuredGrid>\n</VTKFile>\n";
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
                             const ContactSurfaceMesh<2> &,
                             const std::vector<ContactSurfaceNode<2>> &,
                             unsigned int);
    template void
    write_contact_surface<3>(std::ostream &,
                             const ContactSurfaceMesh<3> &,
                             const std::vector<ContactSurfaceNode<3>> &,
                             unsigned int);
  } // namespace io
} // namespace dualcontact
