#pragma once
// The VTU/PVD series' datasets as VTK objects: engine/io/paraview/frame_datasets.hpp defines them
// (every array, without VTK); to_vtk turns one into a vtkUnstructuredGrid (vertices) or a
// vtkPolyData (lines, polygons). The grid occupancy is VTK's alone (it reads the search grid of a
// live run).
#include <cstdint>

#include <vtkSmartPointer.h>

#include "engine/analysis/granule_criterion.hpp"
#include "engine/io/paraview/frame_datasets.hpp"

class vtkDataSet;
class vtkImageData;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace drumlab::render {

using paraview::kParticleArrays;

/// The dataset as VTK holds it: arrays of the same names, types and components, the same
/// active attributes, points in double precision.
vtkSmartPointer<vtkDataSet> to_vtk(const paraview::DataSet& d);

/// paraview::particles(sim, granule) as VTK.
vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const Simulation& sim,
                                                       const GranuleCriterion& granule = {});
/// paraview::particles(frame) as VTK.
vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const SeriesFrame& frame);
/// paraview::bonds(frame) as VTK.
vtkSmartPointer<vtkPolyData> bonds_dataset(const SeriesFrame& frame);
/// paraview::drum(sim, segments) as VTK.
vtkSmartPointer<vtkPolyData> drum_dataset(const Simulation& sim, int segments = 96);
/// paraview::contacts(sim) as VTK.
vtkSmartPointer<vtkPolyData> contacts_dataset(const Simulation& sim);

/// The contact-search grid of the last step with the particles per cell as cell data "particles"
/// (UInt32). Returns null if the search method has no grid (brute force). Throws InputError if the
/// grid has more than max_cells cells.
vtkSmartPointer<vtkImageData> grid_dataset(const Simulation& sim,
                                           std::size_t max_cells = 32u << 20);

}  // namespace drumlab::render
