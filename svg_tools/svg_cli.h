/* SPDX-License-Identifier: MIT */
/* Command-line flags for the XML limits (conica_svg_limits), shared by the
 * tools that read SVG (svgsmooth, scadprofile) so both spell, check and
 * document them the same way. Internal to the tools (not installed). */
#ifndef CONICA_SVG_CLI_H
#define CONICA_SVG_CLI_H

#include "cli_opt.h"
#include "conica_svg.h"

/* Option-table entries (cli_opt.h) for --max-depth, --max-elements,
 * --max-path-bytes, --max-attributes and --max-namespaces with ids
 * first..first+4, in a tool's table (--max-input-bytes is described by
 * each tool: its default differs). Their values go through
 * conica_svg__cli_limit() with the option's full name. */
#define CONICA_SVG_CLI_LIMIT_OPTS(first)                                                       \
    {(first), "max-depth", CLI_ARG_REQUIRED, "N", NULL,                                        \
     "XML element nesting cap (default 256)",                                                 \
     {0, 0, 0}},                                                                               \
        {(first) + 1, "max-elements", CLI_ARG_REQUIRED, "N", NULL,                             \
         "XML element cap (default 1048576)", {0, 0, 0}},                                      \
        {(first) + 2, "max-path-bytes", CLI_ARG_REQUIRED, "N", NULL,                           \
         "cap on one d/points attribute (default 32 MiB)", {0, 0, 0}},                          \
        {(first) + 3, "max-attributes", CLI_ARG_REQUIRED, "N", NULL,                           \
         "cap on the attributes of one element (default 256)", {0, 0, 0}},                     \
        {(first) + 4, "max-namespaces", CLI_ARG_REQUIRED, "N", NULL,                           \
         "cap on the xmlns declarations in scope at one\n"                                     \
         "element (its own and its ancestors', default 64)",                                   \
         {0, 0, 0}}
#define CONICA_SVG_CLI_LIMIT_COUNT 5

/* If flag is --max-input-bytes, --max-depth, --max-elements,
 * --max-path-bytes, --max-attributes or --max-namespaces, read value (a
 * whole number in 1..2147483647) into the matching field of *lim. Returns
 * 1 when the flag was one of these and the value is good, 0 when the flag
 * is none of these (nothing changed), -1 after printing `prog: usage
 * error: ...` for a missing or bad value. */
int conica_svg__cli_limit(const char *prog, const char *flag, const char *value,
                          conica_svg_limits *lim);

#endif
