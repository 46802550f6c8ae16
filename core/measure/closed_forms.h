// Closed-form configuration factors (docs/accuracy-and-closed-forms.md, sections
// 1-4), written independently of the form-factor code they check: the tests
// and the benchmarks measure against them.
#pragma once

namespace bounce {

// Point under the corner of an a x b rectangle at height c, facing it.
double corner_point_rectangle(double a, double b, double c);

// Point facing a parallel rectangle [x0, x1] x [y0, y1] at distance c,
// in coordinates of the rectangle's plane with the point's foot at the
// origin: four corner terms added with their signs (superposition).
double point_parallel_rectangle(double x0, double x1, double y0, double y1, double c);

// The same rectangle seen in a planar mirror (its mirror image, Wallace,
// Cohen & Greenberg 1987): the point faces up at height 0, the rectangle
// at `emitter_height` faces up too (away from the point: it is hidden),
// and a mirror parallel to both at `mirror_height` above it faces down
// with reflectance kr; the point sees the image at 2 mirror - emitter.
double mirrored_point_parallel_rectangle(double x0, double x1, double y0, double y1, double emitter_height,
                                         double mirror_height, double kr);

// Two directly opposed parallel a x b rectangles at distance c.
double parallel_rectangles(double a, double b, double c);

// Rectangles at 90 degrees sharing an edge of length l; from the one of
// width w to the one of width h.
double perpendicular_rectangles(double l, double w, double h);

// Coaxial parallel discs, from radius r1 to radius r2 at distance h.
double coaxial_discs(double r1, double r2, double h);

}  // namespace bounce
