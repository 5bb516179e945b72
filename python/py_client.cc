#include "python/py_client.h"

#include <pybind11/stl.h>

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

#include "driver/jobs/client.h"
#include "driver/jobs/job_query.h"
#include "driver/jobs/job_submit.h"
#include "driver/jobs/job_watch.h"
#include "driver/jobs/store_fetch.h"
#include "python/py_convert.h"

namespace wavebake::python {
namespace {

// f() with the GIL released (an RPC: other Python threads run meanwhile).
template <typename F>
auto Released(F f) {
  py::gil_scoped_release release;
  return f();
}

// The events of one job, from a watching thread to Python's iterator.
class PyWatch {
 public:
  PyWatch(std::shared_ptr<const driver::Client> client, std::string job_id, double patience)
      : client_(std::move(client)) {
    thread_ = std::jthread([this, job_id = std::move(job_id), patience](std::stop_token stop) {
      driver::WatchOptions options{.patience_seconds = patience,
                                   .on_event =
                                       [this](const v1::JobEvent& e) {
                                         std::lock_guard lock(mu_);
                                         queue_.push_back(e);
                                         cv_.notify_one();
                                       },
                                   .stop = stop};
      absl::StatusOr<v1::Job> job = driver::WatchJob(*client_, job_id, options);
      std::lock_guard lock(mu_);
      result_ = std::move(job);
      finished_ = true;
      cv_.notify_one();
    });
  }
  // Stops the stream (an iterator dropped before the job ended) and joins.
  ~PyWatch() {
    py::gil_scoped_release release;
    thread_.request_stop();
    thread_.join();
  }

  py::dict Next() {
    for (;;) {
      std::optional<v1::JobEvent> event;
      bool finished = false;
      {
        py::gil_scoped_release release;
        std::unique_lock lock(mu_);
        cv_.wait_for(lock, std::chrono::milliseconds(100),
                     [&] { return !queue_.empty() || finished_; });
        if (!queue_.empty()) {
          event = std::move(queue_.front());
          queue_.pop_front();
        }
        finished = finished_ && queue_.empty();
      }
      if (event) return MessageToDict(*event);
      if (finished) {
        if (!result_.ok()) Raise(result_.status());
        throw py::stop_iteration();
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
  }
  // The job as it ended (after the iterator is exhausted), else None.
  py::object Job() {
    std::lock_guard lock(mu_);
    if (!finished_ || !result_.ok()) return py::none();
    return MessageToDict(*result_);
  }

 private:
  std::shared_ptr<const driver::Client> client_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<v1::JobEvent> queue_;
  bool finished_ = false;
  absl::StatusOr<v1::Job> result_ = absl::UnknownError("watch still running");
  std::jthread thread_;  // last: joined before the rest goes
};

class PyClient {
 public:
  PyClient(std::string coordinator, std::string token_file, std::string tls_ca,
           double connect_seconds)
      : client_(std::make_shared<const driver::Client>(
            Unwrap(driver::Client::Connect({.coordinator = std::move(coordinator),
                                            .token_file = std::move(token_file),
                                            .tls_ca = std::move(tls_ca)},
                                           connect_seconds)))) {}

  py::dict Submit(const std::string& scene, const py::kwargs& params) {
    v1::BakeRequest request;
    SetRequestFields(request, params);
    absl::StatusOr<v1::Job> job;
    {
      py::gil_scoped_release release;
      job = driver::SubmitScene(*client_, request, scene);
    }
    return MessageToDict(Unwrap(std::move(job)));
  }
  std::unique_ptr<PyWatch> Watch(const std::string& job_id, double patience) {
    return std::make_unique<PyWatch>(client_, job_id, patience);
  }
  py::dict Status(const std::string& job_id) {
    return MessageToDict(Unwrap(Released([&] { return driver::GetJob(*client_, job_id); })));
  }
  py::list Jobs(int limit, bool active_only) {
    std::vector<v1::Job> jobs =
        Unwrap(Released([&] { return driver::ListJobs(*client_, limit, active_only); }));
    py::list out;
    for (const v1::Job& j : jobs) out.append(MessageToDict(j));
    return out;
  }
  py::dict Cancel(const std::string& job_id) {
    return MessageToDict(Unwrap(Released([&] { return driver::CancelJob(*client_, job_id); })));
  }
  py::dict Fetch(const std::string& job_id, const std::string& out) {
    driver::FetchSummary s =
        Unwrap(Released([&] { return driver::FetchStore(*client_, job_id, out); }));
    py::dict d;
    d["files"] = s.files;
    d["bytes"] = s.bytes;
    d["arrays"] = s.arrays;
    d["path"] = out;
    return d;
  }

 private:
  std::shared_ptr<const driver::Client> client_;
};

}  // namespace

void AddClientBindings(py::module_& m) {
  py::class_<PyWatch>(m, "Watch", "The events of a job as an iterator of dicts, to its end.")
      .def("__iter__", [](PyWatch& w) -> PyWatch& { return w; })
      .def("__next__", &PyWatch::Next)
      .def_property_readonly("job", &PyWatch::Job, "the job as it ended, once iterated to the end");
  py::class_<PyClient>(m, "Client", "A client of a running coordinator (wavebake coordinator).")
      .def(py::init<std::string, std::string, std::string, double>(), py::arg("coordinator"),
           py::arg("token_file") = "", py::arg("tls_ca") = "", py::arg("connect_seconds") = 5.0)
      .def("submit", &PyClient::Submit, py::arg("scene"),
           "submit a bake of SCENE (builtin:NAME or a scene file, uploaded once by hash); "
           "keyword arguments are BakeRequest fields; returns the job")
      .def("watch", &PyClient::Watch, py::arg("job_id"), py::arg("patience_seconds") = 60.0,
           "iterate over the job's events until it ends (reconnecting across restarts)")
      .def("status", &PyClient::Status, py::arg("job_id"))
      .def("jobs", &PyClient::Jobs, py::arg("limit") = 100, py::arg("active_only") = false)
      .def("cancel", &PyClient::Cancel, py::arg("job_id"))
      .def("fetch", &PyClient::Fetch, py::arg("job_id"), py::arg("out"),
           "stream the finished store into OUT (which must not exist), verified");
}

}  // namespace wavebake::python
