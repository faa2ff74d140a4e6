#include "fricon/driver/positions.hpp"

#include <stdexcept>

namespace fricon::driver {

Positions::Data::Data(const Data& other) : origin_of(other.origin_of), origins(other.origins) {
  for (std::size_t i = 0; i < origins.size(); ++i)
    index_of.emplace(origins[i], i);
}

Positions::Positions(std::initializer_list<std::pair<const std::string, std::string>> entries) {
  for (const auto& [key, origin] : entries)
    set(key, origin);
}

Positions::Data& Positions::own() {
  if (!data_) {
    data_ = std::make_shared<Data>();
  } else if (data_.use_count() > 1) {
    data_ = std::make_shared<Data>(*data_);
  }
  return *data_;
}

void Positions::set(const std::string& key, const std::string& origin) {
  Data& d = own();
  auto it = d.index_of.find(origin);
  if (it == d.index_of.end()) {
    d.origins.push_back(origin);
    it = d.index_of.emplace(d.origins.back(), d.origins.size() - 1).first;
  }
  d.origin_of.insert_or_assign(key, it->second);
}

const std::string* Positions::find(std::string_view key) const {
  if (!data_) return nullptr;
  const auto it = data_->origin_of.find(key);
  return it == data_->origin_of.end() ? nullptr : &data_->origins[it->second];
}

const std::string& Positions::at(std::string_view key) const {
  const std::string* origin = find(key);
  if (origin == nullptr) throw std::out_of_range("Positions::at: no position recorded for a key");
  return *origin;
}

std::size_t Positions::text_size() const {
  if (!data_) return 0;
  std::size_t n = 0;
  for (const auto& [key, index] : data_->origin_of)
    n += key.size();
  for (const auto& origin : data_->origins)
    n += origin.size();
  return n;
}

std::map<std::string, std::string, std::less<>> Positions::to_map() const {
  std::map<std::string, std::string, std::less<>> out;
  if (!data_) return out;
  for (const auto& [key, index] : data_->origin_of)
    out.emplace(key, data_->origins[index]);
  return out;
}

}  // namespace fricon::driver
