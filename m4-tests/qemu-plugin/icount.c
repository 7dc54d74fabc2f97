/*
 * icount: a QEMU TCG plugin that counts guest instructions executed between region
 * markers and prints "instructions: N" for each region.
 *
 * Markers are the Thumb-2 hint DBG (a no-op that compilers never emit):
 * DBG #1 starts a region, DBG #2 ends it; the markers themselves are not counted
 * (m4-tests' `measure` emits them). Summed regions: DBG #3 starts one, DBG #4 ends it
 * and adds it to a running sum, DBG #5 prints "instructions: S in N regions (most M)"
 * and starts a new sum (`measure_sum`, `report_sum`: many short calls, e.g. every
 * interrupt of a spindle revolution). At exit it prints the total executed.
 *
 * With the argument `profile=FILE` it also writes, at exit, one line per instruction
 * address executed inside regions: "ADDRESS COUNT" (hex, decimal), which
 * `profile.py` folds into per-function counts.
 *
 * Debian ships no qemu-plugin.h, so the few API types and functions used here are
 * declared below as in QEMU 10.0 (plugin API version 4).
 * Build: gcc -O2 -shared -fPIC -o icount.so icount.c
 * Use:   qemu-system-arm ... -plugin ./icount.so -d plugin
 */
#include <inttypes.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef uint64_t qemu_plugin_id_t;
typedef struct qemu_info_t qemu_info_t; /* only passed through */
struct qemu_plugin_tb;
struct qemu_plugin_insn;
enum qemu_plugin_cb_flags { QEMU_PLUGIN_CB_NO_REGS };
typedef void (*vcpu_udata_cb)(unsigned int vcpu_index, void *userdata);
typedef void (*tb_trans_cb)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*udata_cb)(qemu_plugin_id_t id, void *userdata);

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, tb_trans_cb cb);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn, vcpu_udata_cb cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, udata_cb cb, void *userdata);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
size_t qemu_plugin_insn_data(const struct qemu_plugin_insn *insn, void *dest, size_t len);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_outs(const char *string);

__attribute__((visibility("default"))) int qemu_plugin_version = 4;

/* DBG #n is the halfword pair 0xf3af, 0x80f0 | n. */
enum marker { NONE, START, STOP, SUM_START, SUM_STOP, SUM_REPORT };

static uint64_t executed;     /* every instruction so far, markers excluded */
static uint64_t region_start; /* `executed` at the last start marker */
static int in_region;
static uint64_t sum, sum_regions, sum_most; /* summed regions since the last report */

/* Profile: executions per halfword address of the 4 MB flash, inside regions. */
#define FLASH_HALFWORDS (4u << 20 >> 1)
static uint32_t *profile;
static const char *profile_path;

static void on_insn(unsigned int vcpu, void *udata)
{
    executed++;
    uintptr_t addr = (uintptr_t)udata;
    if (profile && in_region && addr / 2 < FLASH_HALFWORDS)
        profile[addr / 2]++;
}

static void on_start(unsigned int vcpu, void *udata)
{
    region_start = executed;
    in_region = 1;
}

static void on_stop(unsigned int vcpu, void *udata)
{
    in_region = 0;
    char line[64];
    snprintf(line, sizeof line, "instructions: %" PRIu64 "\n", executed - region_start);
    qemu_plugin_outs(line);
}

static void on_sum_stop(unsigned int vcpu, void *udata)
{
    in_region = 0;
    uint64_t n = executed - region_start;
    sum += n;
    sum_regions++;
    if (n > sum_most)
        sum_most = n;
}

static void on_sum_report(unsigned int vcpu, void *udata)
{
    char line[96];
    snprintf(line, sizeof line, "instructions: %" PRIu64 " in %" PRIu64 " regions (most %" PRIu64 ")\n", sum,
             sum_regions, sum_most);
    qemu_plugin_outs(line);
    sum = sum_regions = sum_most = 0;
}

static enum marker marker_of(const struct qemu_plugin_insn *insn)
{
    uint16_t hw[2];
    if (qemu_plugin_insn_data(insn, hw, sizeof hw) != sizeof hw || hw[0] != 0xf3af ||
        (hw[1] & 0xfff0) != 0x80f0)
        return NONE;
    switch (hw[1] & 0xf) {
    case 1: return START;
    case 2: return STOP;
    case 3: return SUM_START;
    case 4: return SUM_STOP;
    case 5: return SUM_REPORT;
    default: return NONE;
    }
}

static void on_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    static const vcpu_udata_cb callbacks[] = {[NONE] = on_insn,          [START] = on_start,
                                              [STOP] = on_stop,          [SUM_START] = on_start,
                                              [SUM_STOP] = on_sum_stop,  [SUM_REPORT] = on_sum_report};
    for (size_t i = 0; i < qemu_plugin_tb_n_insns(tb); i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        void *addr = (void *)(uintptr_t)qemu_plugin_insn_vaddr(insn);
        qemu_plugin_register_vcpu_insn_exec_cb(insn, callbacks[marker_of(insn)],
                                               QEMU_PLUGIN_CB_NO_REGS, addr);
    }
}

static void report_total(qemu_plugin_id_t id, void *udata)
{
    char line[64];
    snprintf(line, sizeof line, "total instructions: %" PRIu64 "\n", executed);
    qemu_plugin_outs(line);
    if (!profile)
        return;
    FILE *f = fopen(profile_path, "w");
    if (!f)
        return;
    for (uint32_t i = 0; i < FLASH_HALFWORDS; i++)
        if (profile[i])
            fprintf(f, "%x %" PRIu32 "\n", i * 2, profile[i]);
    fclose(f);
}

__attribute__((visibility("default"))) int
qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (strncmp(argv[i], "profile=", 8) == 0) {
            profile_path = argv[i] + 8;
            profile = calloc(FLASH_HALFWORDS, sizeof *profile);
        }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_translate);
    qemu_plugin_register_atexit_cb(id, report_total, NULL);
    return 0;
}
