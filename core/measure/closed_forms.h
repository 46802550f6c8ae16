// Closed-form configuration factors (docs/accuracy-and-closed-forms.md, sections
// 1-4), written independently of the form-factor code they check: the tests
// and the benchmarks measure against them.
#pragma once

namespace bounce {

// Point under the corner of an a x b rectangle at height c, facing it.
double corner_point_rectangle(double a, double b, double c);

// Two directly opposed parallel a x b rectangles at distance c.
double parallel_rectangles(double a, double b, double c);

// Rectangles at 90 degrees sharing an edge of length l; from the one of
// width w to the one of width h.
double perpendicular_rectangles(double l, double w, double h);

// Coaxial parallel discs, from radius r1 to radius r2 at distance h.
double coaxial_discs(double r1, double r2, double h);

}  // namespace bounce
