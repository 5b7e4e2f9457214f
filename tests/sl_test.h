/* Test cases are named module::case (the function is module_case). */
#ifndef SL_TEST_H
#define SL_TEST_H
#define SL_CASE(module, fn) { #module "::" #fn, module##_##fn, NULL, NULL, NULL }
#endif
