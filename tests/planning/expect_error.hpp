#pragma once
// EXPECT that a call throws `ErrorType` whose message contains `needle` (the field and value a
// bad request must name).
#include <gtest/gtest.h>

#include <string>

#define SCANTLING_EXPECT_ERROR(statement, ErrorType, needle)                          \
    do {                                                                              \
        try {                                                                         \
            statement;                                                                \
            ADD_FAILURE() << "no " #ErrorType " from: " #statement;                   \
        } catch (const ErrorType& error) {                                            \
            EXPECT_NE(std::string(error.what()).find(needle), std::string::npos)      \
                << "message \"" << error.what() << "\" lacks \"" << (needle) << "\""; \
        }                                                                             \
    } while (false)
