/* Stub of the ChibiOS 3.1 RT API the e-puck2 kit uses (see README.md for each line's source).
 * Declarations only: compile against it, never link. */
#ifndef CH_H
#define CH_H

#include <stddef.h>
#include <stdint.h>

#define CH_CFG_ST_FREQUENCY 1000 /* FW2 src/chconf.h */

typedef uint32_t systime_t; /* CH_CFG_ST_RESOLUTION 32 */
typedef uint32_t tprio_t;
typedef uint64_t stkalign_t;
typedef void (*tfunc_t)(void *p);
typedef struct ch_thread thread_t;

#define NORMALPRIO (tprio_t)64

#define PORT_WA_SIZE(n) ((size_t)(n) + 64u)
#define THD_WORKING_AREA_SIZE(n) \
    ((PORT_WA_SIZE(n) + sizeof(stkalign_t) - 1u) / sizeof(stkalign_t) * sizeof(stkalign_t))
#define THD_WORKING_AREA(s, n) stkalign_t s[THD_WORKING_AREA_SIZE(n) / sizeof(stkalign_t)]
#define PORT_THD_FUNCTION(tname, arg) void tname(void *arg)
#define THD_FUNCTION(tname, arg) PORT_THD_FUNCTION(tname, arg)

#define MS2ST(msec) \
    ((systime_t)(((((uint32_t)(msec)) * ((uint32_t)CH_CFG_ST_FREQUENCY)) + 999UL) / 1000UL))

thread_t *chThdCreateStatic(void *wsp, size_t size, tprio_t prio, tfunc_t pf, void *arg);
systime_t chThdSleepUntilWindowed(systime_t prev, systime_t next);
/* A static inline function in ChibiOS (chvt.h, chregistry.h); declared here. */
systime_t chVTGetSystemTime(void);
void chRegSetThreadName(const char *name);

#endif /* CH_H */
