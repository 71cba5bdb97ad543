// docs/model.md is the model's specification, inside the repository. These
// tests keep every reference to it resolvable: no file cites the former
// external specification (the word MODEL, as in "MODEL.md" or "MODEL §7"),
// every "docs/model.md §N" or "model §N" names a section docs/model.md has,
// and every link to a heading of docs/model.md finds it.
//
// The whole source tree is read, except .git, .cache and the top-level
// build* and out directories (as .gitignore), files with a NUL byte, and
// this file, which has to spell out what it looks for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace animat {
namespace {

namespace fs = std::filesystem;

constexpr char kSpec[] = "docs/model.md";
constexpr char kSelf[] = "tests/docs/model_spec_test.cc";
constexpr char kSection[] = "\u00a7";  // The section sign, in UTF-8.

struct TextFile {
  std::string path;  // Relative to the source root, '/'-separated.
  std::string text;
};

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Every text file of the source tree, sorted by path.
std::vector<TextFile> SourceTextFiles() {
  const fs::path root(ANIMAT_SOURCE_DIR);
  std::vector<TextFile> files;
  for (auto it = fs::recursive_directory_iterator(root);
       it != fs::recursive_directory_iterator(); ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_directory()) {
      const bool top = it.depth() == 0;
      if (name == ".git" || name == ".cache" ||
          (top && (name.rfind("build", 0) == 0 || name == "out"))) {
        it.disable_recursion_pending();
      }
      continue;
    }
    if (!it->is_regular_file()) continue;
    std::string text = ReadAll(it->path());
    if (text.find('\0') != std::string::npos) continue;
    std::string path = fs::relative(it->path(), root).generic_string();
    if (path == kSelf) continue;
    files.push_back({std::move(path), std::move(text)});
  }
  std::sort(
      files.begin(), files.end(),
      [](const TextFile& a, const TextFile& b) { return a.path < b.path; });
  return files;
}

const TextFile* Find(const std::vector<TextFile>& files,
                     const std::string& path) {
  for (const TextFile& f : files) {
    if (f.path == path) return &f;
  }
  return nullptr;
}

bool IsWordChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

int LineOf(const std::string& text, size_t offset) {
  return 1 + static_cast<int>(
                 std::count(text.begin(), text.begin() + offset, '\n'));
}

// The line holding `offset`, cut to about 100 bytes around it (at UTF-8
// character boundaries) for messages.
std::string LineAt(const std::string& text, size_t offset) {
  const size_t begin = text.rfind('\n', offset);
  size_t from = begin == std::string::npos ? 0 : begin + 1;
  size_t end = std::min(text.find('\n', offset), text.size());
  if (offset - from > 50) from = offset - 50;
  if (end - offset > 50) end = offset + 50;
  auto continuation = [&](size_t i) {
    return i < text.size() &&
           (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80;
  };
  while (continuation(from)) ++from;
  while (continuation(end)) ++end;
  return text.substr(from, end - from);
}

// A section number at `pos` ("7", "7.6"), or "" when none starts there.
std::string NumberAt(const std::string& text, size_t pos) {
  size_t end = pos;
  while (end < text.size()) {
    if (std::isdigit(static_cast<unsigned char>(text[end]))) {
      ++end;
    } else if (text[end] == '.' && end > pos && end + 1 < text.size() &&
               std::isdigit(static_cast<unsigned char>(text[end + 1]))) {
      ++end;
    } else {
      break;
    }
  }
  return text.substr(pos, end - pos);
}

// The section numbers of docs/model.md's headings ("## 7. Motion physics"
// gives "7", "### 7.6 Integration" gives "7.6"), in order.
std::vector<std::string> SpecSections(const std::string& spec) {
  std::vector<std::string> sections;
  std::istringstream in(spec);
  std::string line;
  bool fenced = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) fenced = !fenced;
    if (fenced || line.rfind("##", 0) != 0) continue;
    const size_t text = line.find_first_not_of('#');
    if (text == std::string::npos || line[text] != ' ') continue;
    const std::string number = NumberAt(line, text + 1);
    if (!number.empty()) sections.push_back(number);
  }
  return sections;
}

// GitHub's anchor of a heading: lower case, spaces to hyphens, other
// punctuation dropped (non-ASCII characters are dropped too; no heading of
// docs/model.md has a non-ASCII letter).
std::string Slug(const std::string& heading) {
  std::string slug;
  for (char c : heading) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u >= 0x80) continue;
    if (std::isalnum(u)) {
      slug += static_cast<char>(std::tolower(u));
    } else if (c == ' ' || c == '-') {
      slug += '-';
    } else if (c == '_') {
      slug += '_';
    }
  }
  return slug;
}

std::set<std::string> SpecAnchors(const std::string& spec) {
  std::set<std::string> anchors;
  std::istringstream in(spec);
  std::string line;
  bool fenced = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) fenced = !fenced;
    if (fenced || line.rfind('#', 0) != 0) continue;
    const size_t text = line.find_first_not_of('#');
    if (text == std::string::npos || line[text] != ' ') continue;
    anchors.insert(Slug(line.substr(text + 1)));
  }
  return anchors;
}

struct Reference {
  std::string where;    // "path:line".
  std::string section;  // "7.6".
  std::string line;     // The line, for the message.
};

// The section numbers cited at `pos` (just after a section sign) and by
// any list that follows: "§4.4 and §8.3", "§2, §3", "§7.2–§7.4".
void ParseCitation(const TextFile& file, size_t pos,
                   std::vector<Reference>* out) {
  const std::string& text = file.text;
  const std::string sign = kSection;
  while (true) {
    const std::string number = NumberAt(text, pos);
    const std::string where =
        file.path + ":" + std::to_string(LineOf(text, pos));
    out->push_back({where, number, LineAt(text, pos)});
    size_t next = pos + number.size();
    bool more = false;
    for (const char* joint : {", ", " and ", ", and ", "\u2013", "-"}) {
      const std::string j = joint;
      if (text.compare(next, j.size(), j) == 0 &&
          text.compare(next + j.size(), sign.size(), sign) == 0) {
        pos = next + j.size() + sign.size();
        more = true;
        break;
      }
    }
    if (!more) return;
  }
}

// Every section the tree cites: "docs/model.md §N", "model.md §N" and
// "model §N" anywhere, and any bare "§N" inside docs/model.md itself.
std::vector<Reference> SectionReferences(const std::vector<TextFile>& files) {
  const std::string sign = kSection;
  std::vector<Reference> references;
  for (const TextFile& file : files) {
    const std::string& text = file.text;
    const bool spec = file.path == kSpec;
    for (size_t at = text.find(sign); at != std::string::npos;
         at = text.find(sign, at + 1)) {
      bool cited = spec;
      for (const char* prefix : {"model ", "model.md "}) {
        const std::string p = prefix;
        if (at >= p.size() && text.compare(at - p.size(), p.size(), p) == 0 &&
            (at == p.size() || !IsWordChar(text[at - p.size() - 1]))) {
          cited = true;
        }
      }
      if (!cited) continue;
      if (NumberAt(text, at + sign.size()).empty()) {
        if (!spec) {
          references.push_back(
              {file.path + ":" + std::to_string(LineOf(text, at)), "",
               LineAt(text, at)});
        }
        continue;
      }
      // A list continues from the first number; skip its later signs.
      std::vector<Reference> list;
      ParseCitation(file, at + sign.size(), &list);
      references.insert(references.end(), list.begin(), list.end());
      for (size_t k = 1; k < list.size(); ++k) at = text.find(sign, at + 1);
    }
  }
  return references;
}

class ModelSpecTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { files_ = new auto(SourceTextFiles()); }
  static void TearDownTestSuite() {
    delete files_;
    files_ = nullptr;
  }
  static const std::vector<TextFile>& files() { return *files_; }
  static const std::string& spec() {
    const TextFile* f = Find(*files_, kSpec);
    static const std::string kEmpty;
    return f ? f->text : kEmpty;
  }

 private:
  static std::vector<TextFile>* files_;
};

std::vector<TextFile>* ModelSpecTest::files_ = nullptr;

TEST_F(ModelSpecTest, TheSpecificationIsInTheRepository) {
  ASSERT_NE(Find(files(), kSpec), nullptr) << "docs/model.md is missing";
  EXPECT_GT(files().size(), 100u)
      << "the source tree was not found at " << ANIMAT_SOURCE_DIR;
}

// §1-§10 are the model's sections in the order code and history cite them
// (genome, network, dynamics, development, signals, body, physics,
// evaluation, evolution, energy and guidance); more may follow.
TEST_F(ModelSpecTest, TopLevelSectionsAreNumberedInOrder) {
  std::vector<std::string> top;
  for (const std::string& s : SpecSections(spec())) {
    if (s.find('.') == std::string::npos) top.push_back(s);
  }
  ASSERT_GE(top.size(), 10u);
  for (size_t i = 0; i < top.size(); ++i) {
    EXPECT_EQ(top[i], std::to_string(i + 1));
  }
  const std::string expected[] = {"## 1. Genome", "## 7. Motion physics",
                                  "## 8. Evaluation", "## 9. Evolution"};
  for (const std::string& heading : expected) {
    EXPECT_NE(spec().find("\n" + heading + "\n"), std::string::npos) << heading;
  }
}

// The word MODEL (upper case, a whole word: "MODEL.md", "MODEL §7",
// "MODEL's", "MODEL v2") cites the specification that used to live outside
// the repository. Only one line of docs/model.md, its history, may name it.
TEST_F(ModelSpecTest, NoFileCitesTheFormerExternalSpecification) {
  int spec_lines = 0;
  int spec_last_line = -1;
  for (const TextFile& file : files()) {
    const std::string& text = file.text;
    for (size_t at = text.find("MODEL"); at != std::string::npos;
         at = text.find("MODEL", at + 1)) {
      const size_t end = at + 5;
      if ((at > 0 && IsWordChar(text[at - 1])) ||
          (end < text.size() && IsWordChar(text[end]))) {
        continue;
      }
      const int line = LineOf(text, at);
      if (file.path == kSpec) {
        if (line != spec_last_line) ++spec_lines;
        spec_last_line = line;
        continue;
      }
      ADD_FAILURE() << file.path << ":" << line
                    << ": cites the former external specification; cite "
                       "docs/model.md (\"docs/model.md §N\") instead:\n"
                    << LineAt(text, at);
    }
  }
  EXPECT_LE(spec_lines, 1) << "docs/model.md names MODEL on more than one "
                              "line";
}

TEST_F(ModelSpecTest, EverySectionReferenceNamesASectionOfDocsModelMd) {
  const std::vector<std::string> sections = SpecSections(spec());
  const std::set<std::string> known(sections.begin(), sections.end());
  ASSERT_FALSE(known.empty());
  const std::vector<Reference> references = SectionReferences(files());
  EXPECT_GT(references.size(), 50u);
  for (const Reference& r : references) {
    EXPECT_TRUE(known.count(r.section) > 0)
        << r.where << ": cites docs/model.md \u00a7" << r.section
        << ", which docs/model.md does not have:\n"
        << r.line;
  }
}

TEST_F(ModelSpecTest, EveryLinkToAHeadingOfDocsModelMdFindsIt) {
  const std::set<std::string> anchors = SpecAnchors(spec());
  int links = 0;
  for (const TextFile& file : files()) {
    const std::string& text = file.text;
    const std::string target = "model.md#";
    for (size_t at = text.find(target); at != std::string::npos;
         at = text.find(target, at + 1)) {
      size_t end = at + target.size();
      while (end < text.size() &&
             (std::isalnum(static_cast<unsigned char>(text[end])) ||
              text[end] == '-' || text[end] == '_')) {
        ++end;
      }
      const std::string anchor =
          text.substr(at + target.size(), end - at - target.size());
      ++links;
      EXPECT_TRUE(anchors.count(anchor) > 0)
          << file.path << ":" << LineOf(text, at) << ": no heading of "
          << "docs/model.md has the anchor #" << anchor;
    }
  }
  EXPECT_GT(links, 0);
}

}  // namespace
}  // namespace animat
