/*!
\ingroup PkgSurfaceMeshMultiresolutionRef
\cgalConcept

The concept `AttributeTraits` maps the value type `T` of an attribute channel (a per-vertex
property map) to a fixed-size array of doubles and back. Relaxation, details and thresholds
all work on these arrays.

\cgalHasModel `CGAL::Surface_mesh_multiresolution::Attribute_traits`
*/
class AttributeTraits
{
public:
  /// the value type of the channel
  typedef unspecified_type T;
  /// the number of doubles that represent one value
  static constexpr std::size_t dimension = unspecified;
  /// the doubles of a value; every component must be finite for valid input
  static std::array<double, dimension> to_array(const T& value);
  /// the value of an array of doubles computed by the package (it may lie outside the
  /// range of `T`: clamp and round as the type needs)
  static T from_array(const std::array<double, dimension>& a);
};
