/* The map FMU's constants shared with its model description (bearing_cosim/map_fmu.py) and its table
 * (bearing_cosim/map_table.py). */
#ifndef BEARING_MAP_CONFIG_H
#define BEARING_MAP_CONFIG_H

#define MODEL_IDENTIFIER BearingMapFMU
#define TABLE_FILE "map_table.bin" /* in resources/ */
#define TABLE_VERSION 1u
/* value references: inputs 0..n_in-1 (Real), outputs VR_OUTPUT + k (the Real outputs, then the Integer ones),
   parameters VR_PARAMETER + k */
#define VR_OUTPUT 1000u
#define VR_PARAMETER 5000u

#endif
