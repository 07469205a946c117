# Estimated seconds of the Catch2 test cases that run longest, so that ctest
# -j2 starts them first on a fresh build. Without a cost, ctest starts tests
# in the order they are declared, and a fresh clone (CI's case: no
# Testing/Temporary/CTestCostData.txt yet) ran its 150 s test near the end of
# the Release list and tens of seconds of ASan tests last, each with the other
# core idle. Once a build has run its tests, ctest's measured costs replace
# these. Included by ctest after the discovered tests (TEST_INCLUDE_FILES in
# tests/CMakeLists.txt); a name that no longer exists is ignored, so a renamed
# test only loses its place in the queue. The long add_test commands get
# their COST where they are declared: ctest reads this file before them.
# Figures: one Release and one ASan run on 2 cores, the larger of the two.
set_tests_properties([=[interruptible without a budget gives full's forces on every step of plates20 and cube_drop, and full keeps the 20-plate stack standing]=] PROPERTIES COST 142)
set_tests_properties([=[a query is charged a unit and a candidate for each tet of an enabled body whose stored box holds the point, before and after motion and after a refresh, in every scene]=] PROPERTIES COST 118)
set_tests_properties([=[degenerate poses: touching objects in 10,000 exact motions: hash = brute force, order-free, motion-free]=] PROPERTIES COST 110)
set_tests_properties([=[interruptible with no budget gives full's forces bit for bit, in both response modes]=] PROPERTIES COST 86)
set_tests_properties([=[on a clock that reads the work charged so far, each stage's time is its work]=] PROPERTIES COST 72)
set_tests_properties([=[stage work adds up to the step's work exactly, for every cycle method]=] PROPERTIES COST 47)
set_tests_properties([=[every registered method finds exactly brute_force's colliding points]=] PROPERTIES COST 47)
set_tests_properties([=[under a work budget two runs are identical apart from timings, whatever the thread count]=] PROPERTIES COST 23)
set_tests_properties([=[neural, approximate: its per-frame verdicts agree with brute_force's on the committed finger path]=] PROPERTIES COST 20)
set_tests_properties([=[fine tasks find exactly the paper's contacts and depths, and brute force's points, for every piece size]=] PROPERTIES COST 20)
set_tests_properties([=[folding_bar: brute_force and full find exactly the oracle's self-collision inside set]=] PROPERTIES COST 19)
