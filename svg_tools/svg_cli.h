/* SPDX-License-Identifier: MIT */
/* Command-line flags for the XML limits (conica_svg_limits), shared by the
 * tools that read SVG (svgsmooth, scadprofile) so both spell, check and
 * document them the same way. Internal to the tools (not installed). */
#ifndef CONICA_SVG_CLI_H
#define CONICA_SVG_CLI_H

#include "conica_svg.h"

/* Help lines for --max-depth, --max-elements, --max-path-bytes,
 * --max-attributes and --max-namespaces
 * (--max-input-bytes is described by each tool: its default differs). */
#define CONICA_SVG_CLI_LIMITS_HELP                                                           \
    "  --max-depth N         XML element nesting cap (default 256)\n"                       \
    "  --max-elements N      XML element cap (default 1048576)\n"                            \
    "  --max-path-bytes N    cap on one d/points attribute (default 32 MiB)\n"             \
    "  --max-attributes N    cap on the attributes of one element (default 256)\n"         \
    "  --max-namespaces N    cap on the xmlns declarations in scope at one element\n"       \
    "                        (its own and its ancestors', default 64)\n"

/* If flag is --max-input-bytes, --max-depth, --max-elements,
 * --max-path-bytes, --max-attributes or --max-namespaces, read value (a
 * whole number in 1..2147483647) into the matching field of *lim. Returns
 * 1 when the flag was one of these and the value is good, 0 when the flag
 * is none of these (nothing changed), -1 after printing `prog: usage
 * error: ...` for a missing or bad value. */
int conica_svg__cli_limit(const char *prog, const char *flag, const char *value,
                          conica_svg_limits *lim);

#endif
