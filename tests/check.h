/* The test suites' checks and runner: a table of {name, function}, and a
   closing line "N passed, N failed". A check that fails prints where. */
#ifndef MESHFIX_TESTS_CHECK_H
#define MESHFIX_TESTS_CHECK_H
#include <stdio.h>
#include <string.h>

static int failures;

#define CHECK(cond)                                                                                     \
    do {                                                                                                \
        if (!(cond)) {                                                                                  \
            printf("    %s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);                         \
            failures++;                                                                                 \
        }                                                                                               \
    } while (0)

#define CHECK_EQ(a, b)                                                                                  \
    do {                                                                                                \
        unsigned long long va_ = (unsigned long long)(a), vb_ = (unsigned long long)(b);                \
        if (va_ != vb_) {                                                                               \
            printf("    %s:%d: %s == %llu, expected %s == %llu\n", __FILE__, __LINE__, #a, va_, #b, vb_); \
            failures++;                                                                                 \
        }                                                                                               \
    } while (0)

typedef struct test_case {
    const char *name;
    void (*run)(void);
} test_case;

/* Runs the tests whose name contains `filter` (all when NULL); returns
   the exit status. */
static int run_tests(const test_case *tests, size_t count, const char *filter)
{
    size_t i, passed = 0, failed = 0;
    for (i = 0; i < count; ++i) {
        int before = failures;
        if (filter != NULL && strstr(tests[i].name, filter) == NULL)
            continue;
        tests[i].run();
        if (failures == before) {
            passed++;
            printf("ok   %s\n", tests[i].name);
        } else {
            failed++;
            printf("FAIL %s\n", tests[i].name);
        }
    }
    printf("%lu passed, %lu failed\n", (unsigned long)passed, (unsigned long)failed);
    return failed != 0;
}
#endif
