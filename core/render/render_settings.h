// RenderSettings: the parameters of Levoy's model that do not depend on the view.
#pragma once

#include <optional>

#include <glm/vec2.hpp>

namespace kdswap {

struct RenderSettings {
  float stepVoxels = 0.5f;          //!< sample spacing, in units of the smallest voxel spacing
  float earlyTermination = 0.99f;   //!< stop a ray once its opacity reaches this; 1 disables
  bool shading = true;              //!< Phong shading from the precomputed gradients
  bool jitter = true;               //!< per-ray lattice phase (Ray::offset) against ring artefacts
  //! Added to every ray's lattice phase (mod 1): passes of one view with different shifts sample
  //! different lattices, and their average (latticePassShift, kdswap render --passes, the desktop
  //! app's refinement) integrates the lattice's rings and grain away.
  float phaseShift = 0.0f;
  bool skipEmptySpace = true;       //!< jump over invisible regions (exact; off only to test that it is)
  //! Skip rays that opaque matter in front of a node's brick ends (exact; see occlusion_grid.h).
  //! It needs every brick's cell summary: gathered in the virtual cluster, merged across MPI ranks.
  bool cullOccluded = true;
  //! Front-to-back waves (beyond the paper; front_transmittance.h): nodes render one after
  //! another, nearest first, each reading the light the nodes in front left at its pixels, so no
  //! node samples behind where the single-node ray stops. Replaces the occlusion map; in-process
  //! only (the virtual cluster with one brick per node), since it passes data while rendering.
  bool frontToBackWaves = false;
  float ambient = 0.3f, diffuse = 0.7f, specular = 0.3f, shininess = 24.0f;
  std::optional<glm::vec2> valueRange;  //!< scalar range mapped to [0, 1]; the volume's if unset
};

}  // namespace kdswap
