!> Contact on RCB parts (docs/contact.md, section 8): the global search run
!> on the parts, each part's local set, and the migration of node data
!> between the mesh owners and the parts. contact_enforce calls these; the
!> contributions of the parts go back to the owners as ordered records
!> (contact_records).
!>
!> Parallel contact by RCB (docs/design.md 5, docs/contact.md 8). The mesh partition
!> does not follow the surfaces, so contact work is decomposed on its own:
!> * At each global search (every few cycles, when the territory margin may be
!>   used up) a recursive coordinate bisection of the owned contact nodes,
!>   weighted by the pairs each node keyed at the last search, gives every
!>   rank a part (a region). Pairs belong to the part of their key node: a DLM
!>   segment pair to the part of its a-segment's first node, a DAM test pair
!>   to the part of its slave node. The ranks owning the segments' zones send
!>   the key items to their part and each segment, with its corners, to every
!>   part its territory (grown, for DLM, by the largest a-segment) may reach;
!>   each part runs the bucket search on what it received and finds exactly
!>   its pairs of the whole search (search_on_parts). Nothing is replicated
!>   but the static surface topology. A part's local set is the segments of
!>   its pairs plus the rings of neighbours the geometry reads (nodal areas,
!>   the DAM master neighbourhood), numbered by global id.
!> * Each stage, mesh owners send x^n, v^n and f of the local sets' nodes to
!>   the parts (point to point), parts run DLM or DAM on their pairs and send
!>   back one record per contribution, keyed by (interface, global pair
!>   order); owners sum the records in key order, which is the order of a
!>   one-rank run, so results are bitwise independent of the rank count.
!>   DAM needs a second round: the owners' matched master velocities go back
!>   to the parts for the put-back-on of the slaves.
!> * DLM with sweeps > 1 (Gauss-Seidel over all pairs) is sequential: every
!>   pair of such an interface goes to part 0, which sends node sums.
!> Nodes far from any pair belong to no local set and cost nothing.
module contact_parts
  use core_kinds, only: rk, ik, i8
  use core_sort, only: sort_order, sort_unique, sorted_find
  use mesh_local, only: mesh_t
  use contact_surface, only: contact_surface_t, surface_node_index, ring_of, local_surface, &
      surface_from_segments
  use contact_search, only: bucket_search, segment_pair_search, search_interval, find_key
  use contact_state, only: contact_t, interface_t, selection_t, PAIR_SEGMENTS, capture_of, &
      key_node, geometry_free, owned_index
  use parallel_env, only: par_max, par_size, par_allgather
  use parallel_exchange, only: par_exchange, par_exchange_counts
  use parallel_rcb, only: rcb_t, rcb_build, rcb_part_of, rcb_parts_of_box
  implicit none
  private
  public :: segment_homes, contact_rebuild, contact_localize, gather_nodes, scatter_nodes
  public :: directory_build

  !> The RCB is cut again at a search whose pairs put more than this times
  !> the mean on one part (when there are at least 16 pairs per part).
  real(rk), parameter :: REBALANCE = 1.2_rk
  !> An item of the search (search_on_parts): interface, kind, index (of a
  !> whole surface's segment, or a node's contact index), face id, the
  !> corners' contact indices (a node: its own, then zeros) and positions.
  integer, parameter :: ITEM = 20
  !> Kinds of items: a key segment (DLM), a candidate segment, a key node
  !> (DAM) and a segment of a key node's ring (DAM).
  integer, parameter :: ITEM_KEY_SEGMENT = 1, ITEM_CANDIDATE = 2, ITEM_KEY_NODE = 3, &
      ITEM_RING = 4

contains

  !> The segments each rank homes: those of its owned zones, whose four
  !> corners it holds (owned or ghost nodes; ghosts move exactly as their
  !> owners). Also the owned nodes that can key pairs, the first RCB weights.
  subroutine segment_homes(ct, mesh)
    type(contact_t), intent(inout) :: ct
    type(mesh_t), intent(in) :: mesh
    integer(i8), allocatable :: zone_key(:)
    integer, allocatable :: perm(:)
    integer :: k, i, n, s

    zone_key = mesh%zone_gid(:mesh%nzone_owned)
    call sort_order(zone_key, perm)
    zone_key = zone_key(perm)
    allocate(ct%key_capable(ct%nown))
    ct%key_capable = .false.
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        call homes_of(p%all_a, p%home_a, p%home_a_node)
        call homes_of(p%all_b, p%home_b, p%home_b_node)
        if (p%method%pair_kind() == PAIR_SEGMENTS) then
          do s = 1, p%all_a%nseg
            i = owned_index(ct, p%all_a%segments(1, s))
            if (i > 0) ct%key_capable(i) = .true.
          end do
          allocate(p%own_slave(0))
        else
          p%own_slave = pack([(n, n = 1, p%all_a%nnode)], &
              [(owned_index(ct, p%all_a%nodes(n)) > 0, n = 1, p%all_a%nnode)])
          do n = 1, size(p%own_slave)
            ct%key_capable(owned_index(ct, p%all_a%nodes(p%own_slave(n)))) = .true.
          end do
        end if
      end associate
    end do
    ct%key_weight = merge(1_i8, 0_i8, ct%key_capable)

  contains

    subroutine homes_of(surf, home, node)
      type(contact_surface_t), intent(in) :: surf
      integer, allocatable, intent(out) :: home(:), node(:, :)
      integer :: j, z, c, m, count
      allocate(home(surf%nseg), node(4, surf%nseg))
      count = 0
      do j = 1, surf%nseg
        ! segment_id = 6 (zone - 1) + face
        z = find_key(zone_key, (surf%segment_id(j) - 1_i8) / 6_i8 + 1_i8)
        if (z == 0) cycle
        z = perm(z)
        count = count + 1
        home(count) = j
        do c = 1, 4
          m = 1
          do while (mesh%node_gid(mesh%zone_node(m, z)) /= ct%all_gid(surf%segments(c, j)))
            m = m + 1
            if (m > 8) error stop 'contact: a segment corner is not a node of its zone'
          end do
          node(c, count) = mesh%zone_node(m, z)
        end do
      end do
      home = home(:count)
      node = node(:, :count)
    end subroutine homes_of

  end subroutine segment_homes


  !> Search of every interface on the RCB parts, this part's pairs and local
  !> set, and the migration plan (the local surfaces follow in
  !> contact_localize, once the local set's positions have arrived). Collective.
  subroutine contact_rebuild(ct, x_old, dt, cycle, sel)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x_old(:, :), dt
    integer(i8), intent(in) :: cycle
    type(selection_t), allocatable, intent(out) :: sel(:)
    integer(i8), allocatable :: request(:), wanted(:), nodes(:), list(:)
    real(rk), allocatable :: mass(:, :, :), owned(:, :, :)
    integer, allocatable :: fill(:), start(:)
    type(rcb_t) :: rcb
    integer :: k, i, m, n, every, every_min, nranks, r, e, j, pass, mine, total
    integer, allocatable :: found(:, :)
    real(rk) :: balance

    nranks = par_size()
    allocate(found(1, nranks))
    ct%rebuilds = ct%rebuilds + 1
    every_min = huge(1)
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        p%margin = p%spec%search_margin
        if (.not. p%margin > 0.0_rk) p%margin = 0.5_rk * p%size
        every = p%spec%search_every
        if (every == 0) every = search_interval(p%margin, capture_of(p, 2.0_rk * ct%speed, dt), &
            2.0_rk * ct%speed, dt, 1.2_rk, 50)
        every_min = min(every_min, every)
      end associate
    end do
    ct%next_search = cycle + int(every_min, i8)

    ! RCB of the owned contact nodes, weighted by the pairs each keyed at the
    ! last search (the search of the parts needs the parts first). When the
    ! pairs found are spread worse than REBALANCE (largest part over the mean:
    ! the load drifted since the last search, e.g. contact began), the RCB is
    ! cut again with the fresh counts and the search repeated on the new parts.
    do pass = 1, 2
      call rcb_build(x_old(:, ct%own_local), ct%key_weight, ct%all_gid(ct%own_contact), &
          nranks, rcb)
      if (nranks > 1) ct%traffic%collectives = ct%traffic%collectives + rcb%reductions
      if (allocated(sel)) deallocate(sel)
      allocate(sel(ct%npair))
      call search_on_parts(ct, x_old, rcb, sel)
      mine = 0
      do k = 1, ct%npair
        mine = mine + size(sel(k)%pairs, 2)
      end do
      ! Every part's pairs (one gather: their sum and their largest).
      call par_allgather([mine], found, ct%traffic)
      total = sum(found)
      call count_keys(ct, sel, total)
      balance = 1.0_rk
      if (total > 0) balance = real(maxval(found), rk) * real(nranks, rk) / real(total, rk)
      ! (A few pairs cost little however they fall.)
      if (pass == 2 .or. .not. balance > REBALANCE .or. total < 16 * nranks) exit
      ct%recuts = ct%recuts + 1
    end do
    if (total > 0) then
      ct%balance_sum = ct%balance_sum + balance
      ct%balance_worst = max(ct%balance_worst, balance)
      ct%balanced_searches = ct%balanced_searches + 1
    end if

    ! The segments this part's pairs read (lists, ascending).
    nodes = [integer(i8) ::]
    do k = 1, ct%npair
      associate(p => ct%pairs(k), pairs => sel(k)%pairs)
        if (p%method%pair_kind() == PAIR_SEGMENTS) then
          ! Nodal areas need every segment of every node.
          sel(k)%seg_a = ring_of(p%all_a, pairs(1, :))
          sel(k)%seg_b = ring_of(p%all_b, pairs(2, :))
        else
          ! The slave nodes' segments; the master neighbourhood, and the
          ! nodal areas of its nodes.
          do pass = 1, 2
            j = 0
            do m = 1, size(pairs, 2)
              n = surface_node_index(p%all_a, pairs(1, m))
              do e = p%all_a%node_start(n), p%all_a%node_start(n + 1) - 1
                j = j + 1
                if (pass == 2) list(j) = int(p%all_a%node_segments(e), i8)
              end do
            end do
            if (pass == 1) allocate(list(j))
          end do
          call sort_unique(list)
          sel(k)%seg_a = int(list)
          deallocate(list)
          sel(k)%seg_b = ring_of(p%all_b, ring_of(p%all_b, pairs(2, :)))
        end if
        nodes = [nodes, int(reshape(p%all_a%segments(:, sel(k)%seg_a), [4 * size(sel(k)%seg_a)]), &
            i8), int(reshape(p%all_b%segments(:, sel(k)%seg_b), [4 * size(sel(k)%seg_b)]), i8)]
      end associate
    end do

    ! The local set, by ascending global id.
    call sort_unique(nodes)
    ct%all_of = int(nodes)
    ct%ncn = size(ct%all_of)
    ct%ncn_max = max(ct%ncn_max, ct%ncn)
    if (allocated(ct%x)) deallocate(ct%x, ct%v, ct%f)
    allocate(ct%x(3, ct%ncn), ct%v(3, ct%ncn), ct%f(3, ct%ncn))

    ! Migration plan: the owners of the local set from the directory; each
    ! owner learns which of its nodes each part needs.
    if (allocated(ct%owner)) deallocate(ct%owner)
    allocate(ct%owner(ct%ncn))
    call owners_of(ct, ct%all_gid(ct%all_of), ct%owner)
    allocate(fill(nranks))
    if (allocated(ct%recv_count)) deallocate(ct%recv_count, ct%send_count)
    allocate(ct%recv_count(nranks), ct%send_count(nranks))
    ct%recv_count = 0
    do i = 1, ct%ncn
      r = ct%owner(i)
      ct%recv_count(r + 1) = ct%recv_count(r + 1) + 1
    end do
    fill(1) = 0
    do r = 2, nranks
      fill(r) = fill(r - 1) + ct%recv_count(r - 1)
    end do
    if (allocated(ct%recv_local)) deallocate(ct%recv_local, ct%owner_pos)
    allocate(ct%recv_local(ct%ncn), request(ct%ncn), ct%owner_pos(ct%ncn))
    start = fill
    do i = 1, ct%ncn
      r = ct%owner(i) + 1
      fill(r) = fill(r) + 1
      ct%owner_pos(i) = fill(r) - start(r)
      ct%recv_local(fill(r)) = i
      request(fill(r)) = int(ct%all_of(i), i8)
    end do
    call par_exchange_counts(ct%recv_count, ct%send_count, ct%traffic)
    call par_exchange(request, ct%recv_count, wanted, ct%send_count, ct%traffic)
    if (allocated(ct%send_own)) deallocate(ct%send_own)
    ! (The receive buffer may be longer than what arrived.)
    allocate(ct%send_own(sum(ct%send_count)))
    do j = 1, size(ct%send_own)
      ct%send_own(j) = owned_index(ct, int(wanted(j)))
    end do
    ! The local set's masses, rigid flags and each interface's offsets from
    ! their owners.
    allocate(owned(1, ct%nown, 2 + ct%npair))
    owned(1, :, 1) = ct%own_mass
    owned(1, :, 2) = merge(1.0_rk, 0.0_rk, ct%own_rigid)
    do k = 1, ct%npair
      owned(1, :, 2 + k) = ct%pairs(k)%offset
    end do
    call scatter_nodes(ct, owned, mass)
    ct%mass = mass(1, :, 1)
    ct%rigid = mass(1, :, 2) > 0.0_rk
    do k = 1, ct%npair
      ct%pairs(k)%loffset = mass(1, :, 2 + k)
    end do
  end subroutine contact_rebuild

  !> The local surfaces and pair lists of this part from the local set's
  !> positions x^n (just gathered); edge flags from the same positions.
  subroutine contact_localize(ct, sel)
    type(contact_t), intent(inout) :: ct
    type(selection_t), intent(in) :: sel(:)
    integer :: k, m

    do k = 1, ct%npair
      associate(p => ct%pairs(k), pairs => sel(k)%pairs, seg_a => sel(k)%seg_a, &
          seg_b => sel(k)%seg_b)
        call local_surface(p%all_a, seg_a, ct%all_of, ct%x, p%a)
        call local_surface(p%all_b, seg_b, ct%all_of, ct%x, p%b)
        ! The sagittas of the local segments (the audit's, at t = 0).
        p%lsag_a = p%sag_a(seg_a)
        p%lsag_b = p%sag_b(seg_b)
        if (p%method%pair_kind() == PAIR_SEGMENTS) then
          p%pairs = reshape([(sorted_find(seg_a, pairs(1, m)), sorted_find(seg_b, pairs(2, m)), &
              m = 1, size(pairs, 2))], [2, size(pairs, 2)])
          ! The global order of a segment pair: the search lists them by (a, b).
          p%pair_key = [(int(pairs(1, m) - 1, i8) * int(p%all_b%nseg, i8) + &
              int(pairs(2, m), i8), m = 1, size(pairs, 2))]
        else
          p%pairs = reshape([(sorted_find(ct%all_of, pairs(1, m)), sorted_find(seg_b, &
              pairs(2, m)), m = 1, size(pairs, 2))], [2, size(pairs, 2)])
        end if
        call geometry_free(p%ga)
        call geometry_free(p%gb)
        call p%method%localized(ct, p)
      end associate
    end do
  end subroutine contact_localize

  !> The global search, on the parts. Segment homes (the ranks owning the
  !> segments' zones) send each segment, with its face id and its corners'
  !> contact indices and positions x^n, to the parts it may reach; a part
  !> searches its keys (DLM: the a-segments whose first node is in its
  !> region; DAM: the slave nodes in its region, each with the segments of
  !> side a around it) against the segments received. A DAM pair (n, b)
  !> needs n inside b's territory, so b goes to every part whose region
  !> meets the territory; a DLM pair (a, b) needs a's box to meet b's
  !> territory, and a's box lies within the largest a-segment extent of its
  !> first node, so b goes to the parts its territory grown by that extent
  !> meets. A part reads nothing but what it received (search_received).
  !> Each part finds exactly its pairs of the whole search, in the same
  !> order. Collective.
  subroutine search_on_parts(ct, x_old, rcb, sel)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x_old(:, :)
    type(rcb_t), intent(in) :: rcb
    type(selection_t), intent(inout) :: sel(:)
    real(rk), allocatable :: send(:), recv(:)
    integer, allocatable :: count(:), recv_count(:), fill(:), parts(:)
    real(rk) :: ext(ct%npair), lo(3), hi(3), grow, slack, corners(3, 4), none(3, 4)
    integer :: k, j, s, i, n, part, np, pass, nranks, q, e, t

    nranks = par_size()
    none = 0.0_rk
    allocate(count(nranks), recv_count(nranks), fill(nranks), parts(nranks))
    ! The largest a-segment extent of each DLM interface.
    do k = 1, ct%npair
      ext(k) = 0.0_rk
      associate(p => ct%pairs(k))
        if (p%method%pair_kind() == PAIR_SEGMENTS) then
          do j = 1, size(p%home_a)
            corners = x_old(:, p%home_a_node(:, j))
            ext(k) = max(ext(k), maxval(maxval(corners, dim=2) - minval(corners, dim=2)))
          end do
        end if
      end associate
      ext(k) = par_max(ext(k), ct%traffic)
    end do

    ! Two passes over the items: count per part, then fill.
    do pass = 1, 2
      if (pass == 1) then
        count = 0
      else
        allocate(send(ITEM * sum(count)))
        fill(1) = 0
        do part = 2, nranks
          fill(part) = fill(part - 1) + count(part - 1)
        end do
      end if
      do k = 1, ct%npair
        associate(p => ct%pairs(k))
          if (p%method%pair_kind() == PAIR_SEGMENTS) then
            do j = 1, size(p%home_a)
              s = p%home_a(j)
              part = 0
              if (.not. p%single_part) part = rcb_part_of(rcb, x_old(:, p%home_a_node(1, j)), &
                  ct%all_gid(p%all_a%segments(1, s)))
              call emit(part, k, ITEM_KEY_SEGMENT, s, p%all_a%segment_id(s), &
                  int(p%all_a%segments(:, s)), x_old(:, p%home_a_node(:, j)))
            end do
            grow = p%margin + ext(k)
          else
            do j = 1, size(p%own_slave)
              n = p%own_slave(j)
              i = owned_index(ct, int(p%all_a%nodes(n)))
              corners = 0.0_rk
              corners(:, 1) = x_old(:, ct%own_local(i))
              part = rcb_part_of(rcb, corners(:, 1), ct%all_gid(ct%own_contact(i)))
              call emit(part, k, ITEM_KEY_NODE, ct%own_contact(i), 0_i8, &
                  [ct%own_contact(i), 0, 0, 0], corners)
              ! The slave node's segments (its ring: the self-contact
              ! exclusions, the lower-side rule, its nodal area).
              do e = p%all_a%node_start(n), p%all_a%node_start(n + 1) - 1
                t = p%all_a%node_segments(e)
                call emit(part, k, ITEM_RING, t, p%all_a%segment_id(t), &
                    int(p%all_a%segments(:, t)), none)
              end do
            end do
            grow = p%margin
          end if
          do j = 1, size(p%home_b)
            s = p%home_b(j)
            corners = x_old(:, p%home_b_node(:, j))
            if (p%single_part) then
              call emit(0, k, ITEM_CANDIDATE, s, p%all_b%segment_id(s), &
                  int(p%all_b%segments(:, s)), corners)
              cycle
            end if
            ! Conservative by a few roundings: more candidates change nothing.
            slack = 1.0e-10_rk * (grow + maxval(abs(corners)))
            lo = minval(corners, dim=2) - grow - slack
            hi = maxval(corners, dim=2) + grow + slack
            call rcb_parts_of_box(rcb, lo, hi, parts, np)
            do q = 1, np
              call emit(parts(q), k, ITEM_CANDIDATE, s, p%all_b%segment_id(s), &
                  int(p%all_b%segments(:, s)), corners)
            end do
          end do
        end associate
      end do
    end do
    call par_exchange_counts(ITEM * count, recv_count, ct%traffic)
    call par_exchange(send, ITEM * count, recv, recv_count, ct%traffic)
    deallocate(send)
    do k = 1, ct%npair
      call search_received(ct%pairs(k), k, recv(:sum(recv_count)), sel(k))
    end do

  contains

    subroutine emit(to, k, kind, idx, sid, corner, corners)
      integer, intent(in) :: to, k, kind, idx
      integer(i8), intent(in) :: sid !< face id (a node: 0)
      integer, intent(in) :: corner(4) !< contact indices of the corners (a node: its own)
      real(rk), intent(in) :: corners(3, 4)
      integer :: at
      if (pass == 1) then
        count(to + 1) = count(to + 1) + 1
        return
      end if
      fill(to + 1) = fill(to + 1) + 1
      at = ITEM * (fill(to + 1) - 1)
      send(at + 1:at + 3) = real([k, kind, idx], rk)
      send(at + 4) = real(sid, rk)
      send(at + 5:at + 8) = real(corner, rk)
      send(at + 9:at + ITEM) = reshape(corners, [12])
    end subroutine emit

  end subroutine search_on_parts

  !> One interface's search on what this part received (search_on_parts'
  !> items, every interface's): the keys, candidates and rings as surfaces
  !> of their own, numbered by a compact index of the contact nodes they
  !> hold (ascending contact index, so every order follows the whole
  !> surfaces'), with the received positions; the pairs in the whole
  !> surfaces' numbering (segment index of a and b, or contact index of the
  !> node and segment index of b), as the search on the whole surfaces
  !> lists them.
  subroutine search_received(p, k, recv, sel)
    type(interface_t), intent(in) :: p
    integer, intent(in) :: k !< the interface
    real(rk), intent(in) :: recv(:) !< the items received (ITEM values each)
    type(selection_t), intent(inout) :: sel
    integer(i8), allocatable :: idx(:), sid(:), node(:)
    integer, allocatable :: kind(:), corner(:, :), order(:), pairs(:, :), key(:), cand(:), &
        ring(:), keys_at(:), cands_at(:), union(:)
    real(rk), allocatable :: xc(:, :), pos(:, :, :)
    type(contact_surface_t) :: sa, sb
    integer :: n, j, m, at, nk, i
    integer(i8) :: lowest

    ! This interface's items, ordered by (kind, index) (stable).
    n = 0
    do j = 1, size(recv) / ITEM
      if (nint(recv(ITEM * (j - 1) + 1)) == k) n = n + 1
    end do
    allocate(idx(n), sid(n), kind(n), corner(4, n), pos(3, 4, n))
    m = 0
    do j = 1, size(recv) / ITEM
      at = ITEM * (j - 1)
      if (nint(recv(at + 1)) /= k) cycle
      m = m + 1
      kind(m) = nint(recv(at + 2))
      idx(m) = nint(recv(at + 3), i8)
      sid(m) = nint(recv(at + 4), i8)
      corner(:, m) = nint(recv(at + 5:at + 8))
      pos(:, :, m) = reshape(recv(at + 9:at + ITEM), [3, 4])
    end do
    call sort_order(reshape([int(kind, i8), idx], [2, n], order=[2, 1]), order)
    ! (a DAM ring segment arrives once for each of its nodes that keys)
    key = pack(order, kind(order) /= ITEM_CANDIDATE .and. kind(order) /= ITEM_RING)
    cand = pack(order, kind(order) == ITEM_CANDIDATE)
    ring = pack(order, kind(order) == ITEM_RING)
    ring = pack(ring, unique_mask(ring))

    ! The compact node index: every corner received, with its position.
    node = int(pack(corner, corner > 0), i8)
    call sort_unique(node)
    allocate(xc(3, size(node)))
    xc = 0.0_rk
    do j = 1, size(key)
      call place(key(j))
    end do
    do j = 1, size(cand)
      call place(cand(j))
    end do

    if (p%method%pair_kind() == PAIR_SEGMENTS) then
      if (p%self) then
        ! One surface: the keys and candidates together (a segment can be
        ! both), by segment index; the self rule (b after a) reads it.
        union = [key, cand]
        call sort_order(idx(union), order)
        union = union(order)
        union = pack(union, unique_mask(union))
        call surface_of(union, sa)
        keys_at = [(position_in(union, key(j)), j = 1, size(key))]
        cands_at = [(position_in(union, cand(j)), j = 1, size(cand))]
        call segment_pair_search(xc, sa, sa, .true., p%margin, pairs, keys_at, cands_at)
        sel%pairs = reshape([(int(idx(union(pairs(1, m)))), int(idx(union(pairs(2, m)))), &
            m = 1, size(pairs, 2))], [2, size(pairs, 2)])
      else
        call surface_of(key, sa)
        call surface_of(cand, sb)
        call segment_pair_search(xc, sa, sb, .false., p%margin, pairs)
        sel%pairs = reshape([(int(idx(key(pairs(1, m)))), int(idx(cand(pairs(2, m)))), &
            m = 1, size(pairs, 2))], [2, size(pairs, 2)])
      end if
    else
      ! The slave surface: the rings of the key nodes; the master: the
      ! candidates.
      call surface_of(ring, sa)
      call surface_of(cand, sb)
      nk = size(key)
      allocate(keys_at(nk))
      do j = 1, nk
        keys_at(j) = surface_node_index(sa, sorted_find(node, int(corner(1, key(j)), i8)))
      end do
      call bucket_search(xc, sa, sb, p%self, p%margin, pairs, keys_at)
      if (p%self) then
        ! The lower side (keep_lower_side): a node pairs with a segment of
        ! higher face id than its own lowest (or, in the reverse pass, not).
        m = 0
        do j = 1, size(pairs, 2)
          i = surface_node_index(sa, pairs(1, j))
          lowest = minval(sa%segment_id(sa%node_segments(sa%node_start(i): &
              sa%node_start(i + 1) - 1)))
          if ((lowest < sb%segment_id(pairs(2, j))) .eqv. p%mirror_of > 0) cycle
          m = m + 1
          pairs(:, m) = pairs(:, j)
        end do
        pairs = pairs(:, :m)
      end if
      sel%pairs = reshape([(int(node(pairs(1, m))), int(idx(cand(pairs(2, m)))), &
          m = 1, size(pairs, 2))], [2, size(pairs, 2)])
    end if

  contains

    !> The received positions of an item's corners (a node: its own).
    subroutine place(item)
      integer, intent(in) :: item
      integer :: cc
      do cc = 1, 4
        if (corner(cc, item) > 0) xc(:, sorted_find(node, int(corner(cc, item), i8))) = &
            pos(:, cc, item)
      end do
    end subroutine place

    !> The items' segments (by item, in the given order) as a surface in the
    !> compact node index.
    subroutine surface_of(items, surf)
      integer, intent(in) :: items(:)
      type(contact_surface_t), intent(inout) :: surf
      integer(ik) :: segs(4, size(items))
      integer :: ii, cc
      do ii = 1, size(items)
        do cc = 1, 4
          segs(cc, ii) = int(sorted_find(node, int(corner(cc, items(ii)), i8)), ik)
        end do
      end do
      call surface_from_segments(segs, sid(items), surf=surf, adjacent=.false.)
    end subroutine surface_of

    !> Of items sorted by index, the first of each index.
    function unique_mask(items) result(first)
      integer, intent(in) :: items(:)
      logical :: first(size(items))
      integer :: ii
      first = .true.
      do ii = 2, size(items)
        first(ii) = idx(items(ii)) /= idx(items(ii - 1))
      end do
    end function unique_mask

    !> Place of an item among the union's (by index).
    integer function position_in(list, item) result(at_)
      integer, intent(in) :: list(:), item
      integer :: lo_, hi_
      lo_ = 1
      hi_ = size(list)
      at_ = 0
      do while (lo_ <= hi_)
        at_ = (lo_ + hi_) / 2
        if (idx(list(at_)) == idx(item)) return
        if (idx(list(at_)) < idx(item)) then
          lo_ = at_ + 1
        else
          hi_ = at_ - 1
        end if
      end do
      at_ = 0
    end function position_in

  end subroutine search_received

  !> Weights of the next RCB: each owned node's pairs keyed at this search
  !> (counted at the owners); when no part found any pair, one for each node
  !> that can key pairs (the weights of the first search). Pairs alone, as a
  !> base weight for every key node would spread the parts over the whole
  !> surfaces and leave a small contact patch on one part (the tubes).
  subroutine count_keys(ct, sel, total)
    type(contact_t), intent(inout) :: ct
    type(selection_t), intent(in) :: sel(:)
    integer, intent(in) :: total !< pairs found by all parts
    integer(i8), allocatable :: send(:), recv(:), key(:)
    integer, allocatable :: count(:), recv_count(:), fill(:), owner(:)
    integer :: k, m, c, pass, nranks, r, j, n
    nranks = par_size()
    allocate(count(nranks), recv_count(nranks), fill(nranks))
    ! The key nodes of this part's pairs and their owners (the directory).
    n = 0
    do k = 1, ct%npair
      n = n + size(sel(k)%pairs, 2)
    end do
    allocate(key(n), owner(n))
    n = 0
    do k = 1, ct%npair
      do m = 1, size(sel(k)%pairs, 2)
        n = n + 1
        key(n) = ct%all_gid(key_node(ct%pairs(k), sel(k)%pairs(:, m)))
      end do
    end do
    call owners_of(ct, key, owner)
    do pass = 1, 2
      n = 0
      if (pass == 1) then
        count = 0
      else
        allocate(send(sum(count)))
        fill(1) = 0
        do r = 2, nranks
          fill(r) = fill(r - 1) + count(r - 1)
        end do
      end if
      do k = 1, ct%npair
        do m = 1, size(sel(k)%pairs, 2)
          c = key_node(ct%pairs(k), sel(k)%pairs(:, m))
          n = n + 1
          r = owner(n) + 1
          if (pass == 1) then
            count(r) = count(r) + 1
          else
            fill(r) = fill(r) + 1
            send(fill(r)) = int(c, i8)
          end if
        end do
      end do
    end do
    call par_exchange_counts(count, recv_count, ct%traffic)
    call par_exchange(send, count, recv, recv_count, ct%traffic)
    ct%key_weight = 0
    do j = 1, sum(recv_count)
      m = owned_index(ct, int(recv(j)))
      ct%key_weight(m) = ct%key_weight(m) + 1_i8
    end do
    ! No pairs anywhere: the key nodes, as before the first search.
    if (total == 0) ct%key_weight = merge(1_i8, 0_i8, ct%key_capable)
  end subroutine count_keys


  !> The rank holding a contact node's entry in the owner directory.
  pure integer function directory_rank(gid, nranks)
    integer(i8), intent(in) :: gid !< global node id
    integer, intent(in) :: nranks
    directory_rank = int(modulo(gid, int(nranks, i8)))
  end function directory_rank

  !> The owner directory (contact_t%dir_gid, dir_owner): each rank sends the
  !> global ids of its owned contact nodes to their directory ranks, which
  !> keep them with the sender, by ascending id. Collective.
  subroutine directory_build(ct)
    type(contact_t), intent(inout) :: ct
    integer(i8), allocatable :: send(:), recv(:)
    integer, allocatable :: count(:), recv_count(:), fill(:), perm(:)
    integer :: i, d, nranks, n, r, at
    nranks = par_size()
    allocate(count(nranks), recv_count(nranks), fill(nranks), send(ct%nown))
    count = 0
    do i = 1, ct%nown
      d = directory_rank(ct%all_gid(ct%own_contact(i)), nranks) + 1
      count(d) = count(d) + 1
    end do
    fill(1) = 0
    do d = 2, nranks
      fill(d) = fill(d - 1) + count(d - 1)
    end do
    do i = 1, ct%nown
      d = directory_rank(ct%all_gid(ct%own_contact(i)), nranks) + 1
      fill(d) = fill(d) + 1
      send(fill(d)) = ct%all_gid(ct%own_contact(i))
    end do
    call par_exchange_counts(count, recv_count)
    call par_exchange(send, count, recv, recv_count)
    n = sum(recv_count)
    if (allocated(ct%dir_gid)) deallocate(ct%dir_gid, ct%dir_owner)
    allocate(ct%dir_owner(n))
    ct%dir_gid = recv(:n)
    at = 0
    do r = 1, nranks
      ct%dir_owner(at + 1:at + recv_count(r)) = r - 1
      at = at + recv_count(r)
    end do
    call sort_order(ct%dir_gid, perm)
    ct%dir_gid = ct%dir_gid(perm)
    ct%dir_owner = ct%dir_owner(perm)
  end subroutine directory_build

  !> The mesh owners of contact nodes given by global id, from the owner
  !> directory (a request to each directory rank and its answer). Collective.
  subroutine owners_of(ct, gid, owner)
    type(contact_t), intent(inout) :: ct
    integer(i8), intent(in) :: gid(:)
    integer, intent(out) :: owner(:) !< (size(gid)) mesh-owner rank of each
    integer(i8), allocatable :: send(:), recv(:), answer(:), back(:)
    integer, allocatable :: count(:), recv_count(:), fill(:), at(:)
    integer :: i, d, nranks, j, e
    nranks = par_size()
    if (nranks == 1) then
      owner = 0
      return
    end if
    allocate(count(nranks), recv_count(nranks), fill(nranks), send(size(gid)), at(size(gid)))
    count = 0
    do i = 1, size(gid)
      d = directory_rank(gid(i), nranks) + 1
      count(d) = count(d) + 1
    end do
    fill(1) = 0
    do d = 2, nranks
      fill(d) = fill(d - 1) + count(d - 1)
    end do
    do i = 1, size(gid)
      d = directory_rank(gid(i), nranks) + 1
      fill(d) = fill(d) + 1
      send(fill(d)) = gid(i)
      at(fill(d)) = i
    end do
    call par_exchange_counts(count, recv_count, ct%traffic)
    call par_exchange(send, count, recv, recv_count, ct%traffic)
    allocate(answer(sum(recv_count)))
    do j = 1, size(answer)
      e = sorted_find(ct%dir_gid, recv(j))
      if (e == 0) error stop 'contact owners_of: a node missing from the owner directory'
      answer(j) = int(ct%dir_owner(e), i8)
    end do
    call par_exchange(answer, recv_count, back, count, ct%traffic)
    do j = 1, size(gid)
      owner(at(j)) = int(back(j))
    end do
  end subroutine owners_of


  !> x^n, v^n and f of the local set from the mesh owners; with full
  !> false only f (the stage's forces: x^n and v^n arrived in an earlier
  !> stage of the same step and are unchanged).
  subroutine gather_nodes(ct, x_old, v_old, force, full)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x_old(:, :), v_old(:, :), force(:, :)
    logical, intent(in) :: full
    real(rk), allocatable :: send(:), recv(:)
    integer :: j, l, i, w
    w = merge(9, 3, full)
    allocate(send(w * size(ct%send_own)))
    do j = 1, size(ct%send_own)
      l = ct%own_local(ct%send_own(j))
      if (full) then
        send(9 * j - 8:9 * j - 6) = x_old(:, l)
        send(9 * j - 5:9 * j - 3) = v_old(:, l)
      end if
      send(w * j - 2:w * j) = force(:, l)
    end do
    call par_exchange(send, w * ct%send_count, recv, w * ct%recv_count, ct%traffic)
    do j = 1, ct%ncn
      i = ct%recv_local(j)
      if (full) then
        ct%x(:, i) = recv(9 * j - 8:9 * j - 6)
        ct%v(:, i) = recv(9 * j - 5:9 * j - 3)
      end if
      ct%f(:, i) = recv(w * j - 2:w * j)
    end do
  end subroutine gather_nodes

  !> Owned values (nc, nown, n) to the local sets (nc, ncn, n): n interfaces.
  subroutine scatter_nodes(ct, owned, local)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: owned(:, :, :)
    real(rk), allocatable, intent(out) :: local(:, :, :)
    real(rk), allocatable :: send(:), recv(:)
    integer :: j, nv, nc, k, i
    nc = size(owned, 1)
    nv = nc * size(owned, 3)
    allocate(send(nv * size(ct%send_own)), local(nc, ct%ncn, size(owned, 3)))
    do j = 1, size(ct%send_own)
      do k = 1, size(owned, 3)
        send(nv * (j - 1) + nc * (k - 1) + 1:nv * (j - 1) + nc * k) = owned(:, ct%send_own(j), k)
      end do
    end do
    call par_exchange(send, nv * ct%send_count, recv, nv * ct%recv_count, ct%traffic)
    do j = 1, ct%ncn
      i = ct%recv_local(j)
      do k = 1, size(owned, 3)
        local(:, i, k) = recv(nv * (j - 1) + nc * (k - 1) + 1:nv * (j - 1) + nc * k)
      end do
    end do
  end subroutine scatter_nodes


end module contact_parts
