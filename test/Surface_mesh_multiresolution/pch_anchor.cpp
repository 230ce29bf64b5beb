// SPDX-License-Identifier: GPL-3.0-or-later
// Anchor of the precompiled header shared by the tests (see CMakeLists.txt).
