// SPDX-License-Identifier: BSD-3-Clause
// ITK first: its IO headers bring ITK's own Eigen, which must come before the system one.
#include <itkImageFileReader.h>
#include <itkImageIOFactory.h>
#include <itkMetaDataObject.h>
#include <itkVectorImage.h>

#include "contourmesh/reconstruct/label_map.h"

#include "detail/image_io.h"

#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

namespace contourmesh {

namespace fs = std::filesystem;

namespace {

std::string describe(const itk::ExceptionObject& e) {
  std::string text = e.GetDescription();
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text.empty() ? std::string("unknown ITK error") : text;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string format_value(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Counts the voxels of every value > 0 of a layer; throws for values that are not labels. Label maps
// are long runs of one value, so the map is consulted once per run.
std::map<int, std::size_t> count_labels(const CtImage& image, const std::string& where) {
  std::map<int, std::size_t> counts;
  const float* data = image.GetBufferPointer();
  const std::size_t n = image.GetPixelContainer()->Size();
  std::size_t p = 0;
  while (p < n) {
    const float v = data[p];
    std::size_t q = p + 1;
    while (q < n && data[q] == v) ++q;
    if (!(v >= 0.0f) || v != std::floor(v) || v > static_cast<float>(std::numeric_limits<int>::max() / 2)) {
      const auto index = image.ComputeIndex(static_cast<CtImage::OffsetValueType>(p));
      throw InvalidInputError(where + ": not a label map: voxel (" + std::to_string(index[0]) + ", " +
                              std::to_string(index[1]) + ", " + std::to_string(index[2]) + ") holds " +
                              format_value(v) +
                              " (labels are integers >= 0; for a CT volume use a threshold instead)");
    }
    if (v > 0.0f) {
      counts[static_cast<int>(v)] += q - p;
      if (counts.size() > kMaxLabels) {
        throw InvalidInputError(where + ": not a label map: more than " + std::to_string(kMaxLabels) +
                                " distinct values (for a CT volume use a threshold instead)");
      }
    }
    p = q;
  }
  return counts;
}

std::string metadata(const itk::MetaDataDictionary& dict, const std::string& key) {
  std::string value;
  if (!itk::ExposeMetaData<std::string>(dict, key, value)) return {};
  return value;
}

std::optional<int> metadata_int(const itk::MetaDataDictionary& dict, const std::string& key, const std::string& where) {
  const std::string text = metadata(dict, key);
  if (text.empty()) return std::nullopt;
  std::size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || text.find_first_not_of(" \t", used) != std::string::npos) {
    throw InvalidInputError(where + ": segment metadata " + key + " is '" + text + "', not an integer");
  }
  return v;
}

// A Slicer .seg.nrrd: the voxel layers (the components of a "list" first axis) and the segments.
LabelMap read_segmentation(const fs::path& path, itk::ImageIOBase* io) {
  const std::string name = path.string();
  const unsigned layers = io->GetNumberOfComponents();
  using LayeredImage = itk::VectorImage<float, 3>;
  {
    double voxels = static_cast<double>(layers);
    for (unsigned d = 0; d < 3; ++d) voxels *= static_cast<double>(io->GetDimensions(d));
    try {
      check_allocation("segmentation of " + std::to_string(layers) + " layer(s)", 0.0, voxels * kVolumeBytesPerVoxel,
                       ResourceLimits{});
    } catch (const LimitError&) {
      rethrow_with_context(name);
    }
  }
  auto reader = itk::ImageFileReader<LayeredImage>::New();
  reader->SetImageIO(io);
  reader->SetFileName(name);
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& e) {
    throw InvalidInputError(name + ": cannot read the segmentation: " + describe(e));
  }
  LayeredImage::Pointer layered = reader->GetOutput();
  const auto region = layered->GetLargestPossibleRegion();
  const auto size = region.GetSize();
  if (size[0] == 0 || size[1] == 0 || size[2] == 0) throw InvalidInputError(name + ": empty segmentation");

  LabelMap map;
  map.has_segment_metadata = true;
  const std::size_t voxels = region.GetNumberOfPixels();
  const float* data = layered->GetBufferPointer();
  for (unsigned l = 0; l < layers; ++l) {
    auto layer = CtImage::New();
    layer->SetRegions(region);
    layer->SetSpacing(layered->GetSpacing());
    layer->SetOrigin(layered->GetOrigin());
    layer->SetDirection(layered->GetDirection());
    layer->Allocate();
    float* out = layer->GetBufferPointer();
    for (std::size_t p = 0; p < voxels; ++p) out[p] = data[p * layers + l];
    map.layers.push_back(layer);
  }
  std::vector<std::map<int, std::size_t>> counts;
  for (unsigned l = 0; l < layers; ++l) {
    counts.push_back(count_labels(*map.layers[l], layers > 1 ? name + " (layer " + std::to_string(l) + ")" : name));
  }

  const itk::MetaDataDictionary& dict = io->GetMetaDataDictionary();
  for (int k = 0;; ++k) {
    const std::string prefix = "Segment" + std::to_string(k) + "_";
    const bool declared =
        dict.HasKey(prefix + "ID") || dict.HasKey(prefix + "Name") || dict.HasKey(prefix + "LabelValue");
    if (!declared) break;
    Label label;
    label.id = metadata(dict, prefix + "ID");
    label.name = metadata(dict, prefix + "Name");
    // Files from before Slicer 4.11 have no _LabelValue / _Layer: one binary layer per segment.
    label.layer = metadata_int(dict, prefix + "Layer", name).value_or(layers > 1 ? k : 0);
    label.value = metadata_int(dict, prefix + "LabelValue", name).value_or(layers > 1 ? 1 : k + 1);
    const std::string what = name + ": segment " + std::to_string(k) +
                             (label.name.empty() ? std::string() : " '" + label.name + "'");
    if (label.layer < 0 || label.layer >= static_cast<int>(layers)) {
      throw InvalidInputError(what + " is in layer " + std::to_string(label.layer) + " but the file has " +
                              std::to_string(layers) + " layer" + (layers == 1 ? "" : "s"));
    }
    if (label.value <= 0)
      throw InvalidInputError(what + " has label value " + std::to_string(label.value) + " (must be > 0)");
    const auto& c = counts[static_cast<std::size_t>(label.layer)];
    const auto it = c.find(label.value);
    label.voxels = it == c.end() ? 0 : it->second;
    map.labels.push_back(std::move(label));
  }
  return map;
}

itk::ImageIOBase::Pointer open_header(const fs::path& path) {
  const std::string name = path.string();
  itk::ImageIOBase::Pointer io = itk::ImageIOFactory::CreateImageIO(name.c_str(), itk::IOFileModeEnum::ReadMode);
  if (!io) return nullptr;
  io->SetFileName(name);
  try {
    io->ReadImageInformation();
  } catch (const itk::ExceptionObject& e) {
    throw InvalidInputError(name + ": cannot read the image header: " + describe(e));
  }
  return io;
}

}  // namespace

std::string Label::display_name() const { return name.empty() ? std::to_string(value) : name; }

namespace {

LabelMap from_image(CtImage::Pointer image, const std::string& where) {
  if (!image) throw InvalidInputError(where + ": no image");
  LabelMap map;
  map.layers.push_back(image);
  for (const auto& [value, voxels] : count_labels(*image, where)) {
    Label label;
    label.value = value;
    label.voxels = voxels;
    map.labels.push_back(label);
  }
  return map;
}

std::string list_labels(const LabelMap& map) {
  std::string list;
  for (const Label& l : map.labels) {
    list += (list.empty() ? "" : ", ") +
            (l.name.empty() ? std::to_string(l.value) : "'" + l.name + "' (" + std::to_string(l.value) + ")");
  }
  return list.empty() ? std::string("none") : list;
}

}  // namespace

LabelMap label_map_from_image(CtImage::Pointer image) { return from_image(std::move(image), "label map"); }

LabelMap read_label_map(const fs::path& path) {
  detail::register_image_io_factories();
  const std::string name = path.string();
  std::error_code ec;
  if (fs::is_regular_file(path, ec) && fs::file_size(path, ec) > 0 && !ec) {
    if (itk::ImageIOBase::Pointer io = open_header(path)) {
      const itk::MetaDataDictionary& dict = io->GetMetaDataDictionary();
      const bool segments =
          dict.HasKey("Segment0_ID") || dict.HasKey("Segment0_Name") || dict.HasKey("Segment0_LabelValue");
      if (segments || io->GetNumberOfComponents() > 1) {
        if (io->GetNumberOfDimensions() != 3) {
          throw InvalidInputError(name + ": a segmentation of " + std::to_string(io->GetNumberOfDimensions()) +
                                  " dimensions with " + std::to_string(io->GetNumberOfComponents()) +
                                  " layer(s); expected 3-D voxels, layered along a first 'list' axis");
        }
        return read_segmentation(path, io);
      }
    }
  }
  // A plain label map: read as a volume (the same checks and messages), then its values.
  return from_image(read_volume(path), name);
}

std::vector<Label> select_labels(const LabelMap& map, std::string_view spec) {
  std::vector<Label> selected;
  const std::string text(spec);
  if (text.find_first_not_of(" \t,") == std::string::npos)
    throw InvalidInputError("no label given (use a value, a name or 'all')");
  if (lower(text) == "all") {
    for (const Label& l : map.labels) {
      if (l.voxels > 0) selected.push_back(l);
    }
    if (selected.empty()) throw InvalidInputError("the label map holds no label (every voxel is 0)");
    return selected;
  }
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    start = comma == std::string::npos ? text.size() + 1 : comma + 1;
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    if (item.empty()) continue;
    const Label* found = nullptr;
    for (const Label& l : map.labels) {  // a name first, exactly
      if (!l.name.empty() && l.name == item) found = found ? found : &l;
    }
    if (!found) {
      std::size_t used = 0;
      int value = 0;
      try {
        value = std::stoi(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == item.size()) {
        for (const Label& l : map.labels) {
          if (l.value == value && !found) found = &l;
        }
      }
    }
    if (!found) {
      for (const Label& l : map.labels) {
        if (!l.name.empty() && lower(l.name) == lower(item) && !found) found = &l;
      }
    }
    if (!found) throw InvalidInputError("no label '" + item + "' in the label map (it holds " + list_labels(map) + ")");
    const bool duplicate = std::any_of(selected.begin(), selected.end(), [&](const Label& l) {
      return l.layer == found->layer && l.value == found->value;
    });
    if (!duplicate) selected.push_back(*found);
  }
  return selected;
}

CtImage::Pointer label_mask(const LabelMap& map, const Label& label) {
  if (label.layer < 0 || static_cast<std::size_t>(label.layer) >= map.layers.size() || !map.layers[label.layer]) {
    throw InvalidInputError("label '" + label.display_name() + "': layer " + std::to_string(label.layer) +
                            " is not in the label map");
  }
  const CtImage& layer = *map.layers[label.layer];
  const auto size = layer.GetLargestPossibleRegion().GetSize();
  const float value = static_cast<float>(label.value);
  const float* data = layer.GetBufferPointer();
  std::array<long, 3> lo{std::numeric_limits<long>::max(), std::numeric_limits<long>::max(),
                         std::numeric_limits<long>::max()};
  std::array<long, 3> hi{-1, -1, -1};
  for (long k = 0, p = 0; k < static_cast<long>(size[2]); ++k) {
    for (long j = 0; j < static_cast<long>(size[1]); ++j) {
      for (long i = 0; i < static_cast<long>(size[0]); ++i, ++p) {
        if (data[p] != value) continue;
        const std::array<long, 3> at{i, j, k};
        for (int d = 0; d < 3; ++d) {
          lo[d] = std::min(lo[d], at[d]);
          hi[d] = std::max(hi[d], at[d]);
        }
      }
    }
  }
  if (hi[0] < 0) throw InvalidInputError("label '" + label.display_name() + "' has no voxels");
  // One voxel of background on every side, beyond the map's extent where the label touches it: the
  // surface then closes half a voxel outside the label's last voxels, as its voxels' volume does.
  CtImage::SizeType out_size;
  CtImage::IndexType first;
  for (int d = 0; d < 3; ++d) {
    first[d] = lo[d] - 1;
    out_size[d] = static_cast<CtImage::SizeValueType>(hi[d] - lo[d] + 3);
  }
  auto mask = CtImage::New();
  CtImage::RegionType region;
  region.SetSize(out_size);
  mask->SetRegions(region);
  mask->SetSpacing(layer.GetSpacing());
  mask->SetDirection(layer.GetDirection());
  CtImage::PointType origin;
  layer.TransformIndexToPhysicalPoint(first, origin);
  mask->SetOrigin(origin);
  mask->Allocate();
  mask->FillBuffer(0.0f);
  float* out = mask->GetBufferPointer();
  for (long k = lo[2]; k <= hi[2]; ++k) {
    for (long j = lo[1]; j <= hi[1]; ++j) {
      const float* row = data + (k * static_cast<long>(size[1]) + j) * static_cast<long>(size[0]);
      float* dst = out +
                   ((k - first[2]) * static_cast<long>(out_size[1]) + (j - first[1])) * static_cast<long>(out_size[0]) -
                   first[0];
      for (long i = lo[0]; i <= hi[0]; ++i) dst[i] = row[i] == value ? kLabelMaskInside : 0.0f;
    }
  }
  return mask;
}

Reconstruction reconstruct_label(const LabelMap& map, const Label& label, ReconstructionOptions options,
                                 const ProgressCallback& progress) {
  const std::string what = "label '" + label.display_name() + "'" +
                           (label.name.empty() ? std::string() : " (" + std::to_string(label.value) + ")");
  options.segmentation.threshold_method = ThresholdMethod::Fixed;
  options.segmentation.threshold = 0.5 * kLabelMaskInside;
  options.segmentation.smoothing = ImageSmoothing::None;
  try {
    const CtImage::Pointer mask = label_mask(map, label);
    return reconstruct(*mask, options, progress);
  } catch (const InvalidInputError&) {
    rethrow_with_context(what);  // keeps the type: DivergenceError, TopologyError, LimitError, ...
  }
}

std::string label_file_tag(const Label& label) {
  const std::string name = label.display_name();
  std::string tag;
  bool gap = false;
  for (const unsigned char c : name) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.') {
      if (gap && !tag.empty()) tag += '_';
      tag += static_cast<char>(c);
      gap = false;
    } else {
      gap = true;
    }
  }
  while (!tag.empty() && tag.front() == '.') tag.erase(tag.begin());  // no hidden files
  return tag.empty() ? std::to_string(label.value) : tag;
}

}  // namespace contourmesh
