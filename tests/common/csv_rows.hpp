#pragma once
// A CSV the CLI wrote (localization.csv, metadata.csv ...) as rows of named cells: the header's
// names, each row's cells by position (no quoting: the tests read files whose cells hold none). A
// row shorter than the header leaves its last names out, so `.at(name)` fails loudly.
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace trn::test {

inline std::vector<std::map<std::string, std::string>> read_csv_rows(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    std::vector<std::string> names;
    std::stringstream header(line);
    for (std::string name; std::getline(header, name, ',');) names.push_back(name);
    std::vector<std::map<std::string, std::string>> rows;
    while (std::getline(in, line)) {
        std::map<std::string, std::string> row;
        std::size_t i = 0, start = 0;
        for (std::size_t e; i < names.size(); ++i, start = e + 1) {
            e = line.find(',', start);
            row[names[i]] = line.substr(start, e == std::string::npos ? std::string::npos : e - start);
            if (e == std::string::npos) break;
        }
        rows.push_back(row);
    }
    return rows;
}

}  // namespace trn::test
