// The multipart/form-data parser of the patient upload: what a browser's FormData sends, and each
// malformed body refused with what is wrong.
#include <gtest/gtest.h>

#include "net/MultipartForm.hpp"

namespace orthosim::net {
namespace {

const std::string kBody =
    "--XyZ\r\n"
    "Content-Disposition: form-data; name=\"id\"\r\n\r\n"
    "patient-1\r\n"
    "--XyZ\r\n"
    "Content-Disposition: form-data; name=\"skin\"; filename=\"my skin;1.stl\"\r\n"
    "Content-Type: model/stl\r\n\r\n"
    "solid\r\n--Xy\r\nbinary data\r\n"
    "--XyZ--\r\n";

TEST(MultipartForm, PartsKeepTheirFieldsFileNamesAndBytes) {
  EXPECT_EQ(formBoundary("multipart/form-data; boundary=XyZ"), "XyZ");
  EXPECT_EQ(formBoundary("Multipart/Form-Data; charset=utf-8; boundary=\"a b\""), "a b");
  const std::vector<FormPart> parts = parseMultipartForm(kBody, "XyZ");
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].name, "id");
  EXPECT_EQ(parts[0].fileName, "");
  EXPECT_EQ(parts[0].data, "patient-1");
  EXPECT_EQ(parts[1].name, "skin");
  EXPECT_EQ(parts[1].fileName, "my skin;1.stl");
  EXPECT_EQ(parts[1].contentType, "model/stl");
  // A line that starts like the boundary but is not it stays data.
  EXPECT_EQ(parts[1].data, "solid\r\n--Xy\r\nbinary data");
}

TEST(MultipartForm, BinaryDataWithNulBytesIsKept) {
  const std::string data("a\0b\r\nc", 6);
  const std::string body =
      "--B\r\nContent-Disposition: form-data; name=\"f\"; filename=\"x\"\r\n\r\n" + data + "\r\n--B--\r\n";
  const std::vector<FormPart> parts = parseMultipartForm(body, "B");
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].data, data);
}

TEST(MultipartForm, MalformedBodiesAreRefusedWithWhatIsWrong) {
  auto message = [](const std::string& body) {
    try {
      parseMultipartForm(body, "B");
    } catch (const FormError& e) {
      return std::string(e.what());
    }
    return std::string("parsed");
  };
  EXPECT_NE(message("no parts here").find("no part"), std::string::npos);
  EXPECT_NE(message("--B\r\nContent-Disposition: form-data; name=\"a\"\r\n\r\nvalue cut off").find("cut off"),
            std::string::npos);
  EXPECT_NE(message("--B\r\nContent-Disposition: form-data\r\n\r\nx\r\n--B--").find("no field name"),
            std::string::npos);
  EXPECT_NE(message("--B\r\nContent-Disposition: form-data; name=\"a\"\r\nx\r\n--B--").find("blank line"),
            std::string::npos);
  EXPECT_THROW(formBoundary("application/json"), FormError);
  EXPECT_THROW(formBoundary("multipart/form-data"), FormError);
}

}  // namespace
}  // namespace orthosim::net
