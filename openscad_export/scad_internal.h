/* SPDX-License-Identifier: MIT */
/* Internal helpers of the OpenSCAD export library (conica__scad_ prefix). */
#ifndef CONICA_SCAD_INTERNAL_H
#define CONICA_SCAD_INTERNAL_H

#include "conica_scad.h"

/* libcore's status helpers conica__fail()/conica__ok() and its exact
 * orientation conica__orient2d() (libconica.a is always linked after this
 * library). */
#include "internal.h"

/* Twice the signed area of a closed contour (counter-clockwise > 0). */
double conica__scad_area2(const double *xy, size_t n);

/* Squared distance from p to the segment a-b. */
double conica__scad_seg_dist2(const double *p, const double *a, const double *b);

#endif
