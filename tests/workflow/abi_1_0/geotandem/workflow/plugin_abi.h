/* FROZEN COPY of geotandem/workflow/plugin_abi.h as released at interface version 1.0. Never edit:
 * tests build a plugin against it to check that newer hosts still load 1.0 plugins. */
/* geotandem plugin interface, C ABI.
 *
 * A plugin is a shared library named `geotandem_<name>.so` that exports one function,
 * `geotandem_plugin_entry`, returning a pointer to a static descriptor. Only C types cross the
 * boundary. The descriptor carries its own size and the interface version it was built for; the
 * host refuses a plugin whose major version differs from its own, or whose descriptor is smaller
 * than the host needs, and says which versions it saw and which file.
 *
 * Version policy: a new major version changes or removes something; a minor version only appends
 * fields at the end of the descriptor (the host reads them only when struct_size covers them).
 *
 * Errors: every callback returns 0 on success; on failure it returns non-zero and writes a
 * NUL-terminated message of at most `error_size` bytes into `error`. A plugin must never throw a
 * C++ exception across this boundary (catch everything in the callback). */
#ifndef GEOTANDEM_WORKFLOW_PLUGIN_ABI_H
#define GEOTANDEM_WORKFLOW_PLUGIN_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define GEOTANDEM_PLUGIN_ABI_MAJOR 1
#define GEOTANDEM_PLUGIN_ABI_MINOR 0
#define GEOTANDEM_PLUGIN_ENTRY_NAME "geotandem_plugin_entry"

typedef enum gt_param_type {
  GT_PARAM_INT = 1,    /* 64-bit integer */
  GT_PARAM_FLOAT = 2,  /* double */
  GT_PARAM_BOOL = 3,   /* true / false */
  GT_PARAM_STRING = 4, /* free text */
  GT_PARAM_CHOICE = 5  /* one of `choices`, a '|'-separated list */
} gt_param_type;

/* One parameter the plugin accepts. Drives recipe validation, `geotandem plugins NAME` and docs. */
typedef struct gt_param_spec {
  const char* name; /* recipe key, [a-z0-9_]+ */
  gt_param_type type;
  const char* default_value; /* as text; NULL: the parameter is required */
  const char* help;          /* one sentence, with the unit */
  double min_value;          /* for INT and FLOAT: inclusive bounds; ignored when min > max */
  double max_value;
  const char* choices; /* for CHOICE: "a|b|c"; NULL otherwise */
} gt_param_spec;

/* Parameter values, validated by the host against the specs before any callback is made. */
typedef struct gt_param_value {
  const char* name;
  int64_t int_value;
  double float_value;
  int bool_value;
  const char* text_value; /* STRING and CHOICE */
} gt_param_value;

typedef struct gt_params {
  const gt_param_value* values; /* one per spec, in spec order */
  uint32_t count;
} gt_params;

/* The cube an attribute computes on: shape (inline, crossline, sample), sample interval and unit. */
typedef struct gt_cube_info {
  int64_t shape[3];
  double dz;
  int z_unit_is_ms; /* 1: time (ms); 0: depth (m) */
  double bin_i;     /* metres between inlines */
  double bin_j;     /* metres between crosslines */
} gt_cube_info;

/* An index box [lo, hi) per axis; samples in C order, sample axis fastest. */
typedef struct gt_box {
  int64_t lo[3];
  int64_t hi[3];
} gt_box;

typedef enum gt_plugin_kind { GT_PLUGIN_ATTRIBUTE = 1 } gt_plugin_kind;

/* An attribute maps one input volume to one output volume of the same shape. For an output box
 * the host reads the input over the box grown by the halo and clipped to the cube, then calls
 * compute. Boundary handling inside the cube's edge is the plugin's (mirror is customary); the
 * result for a box must not depend on how the cube is cut into boxes. */
typedef struct gt_attribute_ops {
  /* Halo in samples along (inline, crossline, sample) that `compute` needs around a box. */
  int (*halo)(const gt_params* params, const gt_cube_info* cube, int64_t halo[3], char* error, size_t error_size);
  int (*compute)(const gt_params* params, const gt_cube_info* cube, const float* input, const gt_box* input_box,
                 float* output, const gt_box* output_box, char* error, size_t error_size);
} gt_attribute_ops;

typedef struct gt_plugin_descriptor {
  uint32_t struct_size; /* sizeof(gt_plugin_descriptor) as the plugin was built */
  uint32_t abi_major;   /* GEOTANDEM_PLUGIN_ABI_MAJOR as the plugin was built */
  uint32_t abi_minor;
  gt_plugin_kind kind;
  const char* name;    /* the name recipes use: [a-z0-9_]+ */
  const char* version; /* the plugin's own version, free text */
  const char* summary; /* one line */
  const gt_param_spec* params;
  uint32_t param_count;
  gt_attribute_ops attribute; /* for GT_PLUGIN_ATTRIBUTE */
} gt_plugin_descriptor;

typedef const gt_plugin_descriptor* (*gt_plugin_entry_fn)(void);

#ifdef __cplusplus
}
#endif

/* A plugin defines its entry point with this macro:
 *   GEOTANDEM_PLUGIN_EXPORT const gt_plugin_descriptor* geotandem_plugin_entry(void) { ... } */
#ifdef __cplusplus
#define GEOTANDEM_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))
#else
#define GEOTANDEM_PLUGIN_EXPORT __attribute__((visibility("default")))
#endif

#endif /* GEOTANDEM_WORKFLOW_PLUGIN_ABI_H */
